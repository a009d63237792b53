// Status and StatusOr: how core reports bad user input or configuration.
//
// Programmer errors are assert()s; anything a user can cause (a bad file, an
// unreachable pose, a singular pose set) comes back as a Status whose message
// a person can act on, e.g.
//
//   StatusOr<Robot> robot = LoadRobot("robot.yaml");
//   if (!robot.ok()) { std::cerr << robot.status().message() << "\n"; return 2; }
//   Use(*robot);
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace hexcal {

class Status {
 public:
  Status() = default;  // OK
  static Status Ok() { return Status(); }
  static Status Error(std::string message) { return Status(std::move(message), false); }
  // A long job stopped by its caller: not a success, not a failure.
  static Status Cancelled(std::string message = "cancelled") { return Status(std::move(message), true); }

  bool ok() const { return !failed_; }
  bool cancelled() const { return cancelled_; }
  const std::string& message() const { return message_; }

 private:
  Status(std::string message, bool cancelled) : message_(std::move(message)), failed_(true), cancelled_(cancelled) {}
  std::string message_;
  bool failed_ = false;
  bool cancelled_ = false;
};

template <typename T>
class StatusOr {
 public:
  StatusOr(T value) : value_(std::move(value)) {}         // NOLINT: implicit by design
  StatusOr(Status status) : status_(std::move(status)) {  // NOLINT
    assert(!status_.ok() && "StatusOr needs a value or an error");
  }

  bool ok() const { return value_.has_value(); }
  const Status& status() const { return status_; }
  const T& value() const& {
    assert(ok());
    return *value_;
  }
  T& value() & {
    assert(ok());
    return *value_;
  }
  T&& value() && {
    assert(ok());
    return std::move(*value_);
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

 private:
  std::optional<T> value_;
  Status status_;
};

}  // namespace hexcal
