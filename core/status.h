// Status and StatusOr: how every layer reports a fault a user can meet.
//
// Programmer errors are assert()s; anything a user can cause (a bad file, an
// unreachable pose, a singular pose set, a full disk) comes back as a Status
// of one tier (StatusKind) whose message a person can act on, e.g.
//
//   StatusOr<Robot> robot = LoadRobot("robot.yaml");
//   if (!robot.ok()) return cli::ReportError(std::cerr, "robot check", robot.status());
//   Use(*robot);
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace hexcal {

// What went wrong, for the front ends: the CLI maps it to an exit code in one
// place (ExitCodeFor in app/commands/cli_common.h; the table is in
// docs/cli.md), the GUI to a dialog or a status line.
//
// The tier says what the user can do about it:
// - kBadInput: change the command or the file. An option or a value out of
//   range, a file whose contents do not parse, and a path that names the
//   wrong thing: a missing input, a folder or a FIFO where a file is wanted,
//   a file in the way of a folder, an output that exists without --force.
// - kIo: the path is right but the system refused or failed the operation:
//   permission denied, a read-only or full disk, a failed read, write, fsync,
//   rename, remove or lock, a camera or a controller that cannot be opened or
//   connected to. FileSystemError (core/atomic_file.h) sorts an errno into
//   these two. A device that drops a frame or a reply during a run fails that
//   pose (kFailed), and the run goes on.
// - kFailed: the input was accepted but the computation did not succeed (no
//   convergence, too few usable poses or views).
// - kBusy: another writer holds the session; try again or wait.
enum class StatusKind {
  kOk,
  kBadInput,   // the user's option, value, file contents or path is wrong
  kFailed,     // the computation failed (no convergence, too few usable poses)
  kCancelled,  // a long job stopped by its caller: not a success, not a failure
  kIo,         // the disk, a device or the network refused a sound request
  kBusy,       // the session is in use by another writer (core/session_lock.h)
};

class Status {
 public:
  Status() = default;  // OK
  static Status Ok() { return Status(); }
  // One factory per tier (StatusKind says which fault is which); there is no
  // generic "error", so every new failure picks its tier.
  static Status BadInput(std::string message) { return Status(std::move(message), StatusKind::kBadInput); }
  static Status Failed(std::string message) { return Status(std::move(message), StatusKind::kFailed); }
  static Status IoError(std::string message) { return Status(std::move(message), StatusKind::kIo); }
  static Status Busy(std::string message) { return Status(std::move(message), StatusKind::kBusy); }
  static Status Cancelled(std::string message = "cancelled") {
    return Status(std::move(message), StatusKind::kCancelled);
  }

  // A bad value of one option (out of its range, not one of its choices, in
  // the wrong form), named by its descriptor key (core/option_spec.h):
  // "settle: must be at most 600 s, got 900". The lower layers know the key,
  // not how a front end spells the option: the CLI shows it as its flag, the
  // GUI as its label (WithOptionName).
  static Status BadOption(const std::string& key, std::string detail) {
    return BadInput(std::move(detail)).AboutOption(key);
  }

  bool ok() const { return kind_ == StatusKind::kOk; }
  bool cancelled() const { return kind_ == StatusKind::kCancelled; }
  StatusKind kind() const { return kind_; }
  const std::string& message() const { return message_; }
  // The key of the option the error is about ("" for none); the message then
  // starts with "key: ".
  const std::string& option() const { return option_; }

  // The same error, about the option `key`: "key: " before its message (a
  // file the option named could not be read, a count the option asked for
  // could not be met).
  Status AboutOption(const std::string& key) const {
    Status about = *this;
    if (ok()) return about;
    about.message_ = key + ": " + message_;
    about.option_ = key;
    return about;
  }

  // The same error with its option called `name` (a flag, a label) instead
  // of its key; any other error is returned as it is.
  Status WithOptionName(const std::string& name) const {
    Status named = *this;
    if (option_.empty()) return named;
    named.message_ = name + message_.substr(option_.size());
    named.option_.clear();
    return named;
  }

  // The same error, its message after `prefix` (e.g. the file it is about).
  Status Prefixed(const std::string& prefix) const {
    Status prefixed = *this;
    if (ok()) return prefixed;
    prefixed.message_ = prefix + message_;
    prefixed.option_.clear();  // the message no longer starts with the key
    return prefixed;
  }

  // The same error, `hint` after its message when it is bad input (the hint
  // says what to change: "(a camera file, or the built-in name ...)"); any
  // other tier is returned as it is, since the hint would not fix it.
  Status WithHint(const std::string& hint) const {
    Status hinted = *this;
    if (kind_ == StatusKind::kBadInput) hinted.message_ += hint;
    return hinted;
  }

  // The same error as a failed computation: for a step whose input was
  // accepted but whose work did not succeed (a cancel stays a cancel).
  Status AsFailure() const {
    Status failure = *this;
    if (kind_ == StatusKind::kBadInput) failure.kind_ = StatusKind::kFailed;
    return failure;
  }

 private:
  Status(std::string message, StatusKind kind) : message_(std::move(message)), kind_(kind) {}
  std::string message_;
  StatusKind kind_ = StatusKind::kOk;
  std::string option_;  // AboutOption's key; message_ starts with it and ": "
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
