#include "devices/line_client.h"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace hexcal::workflow {
namespace {

using Clock = std::chrono::steady_clock;

// A send that cannot go out within this time means the peer stopped reading.
constexpr std::chrono::milliseconds kSendTimeout{5000};

int RemainingMs(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left > 0 ? static_cast<int>(left) : 0;
}

// Waits for `events` on `fd` until `deadline`; EINTR restarts the wait.
// Returns poll's revents, 0 on time-out, -1 on error (errno set).
int WaitFor(int fd, short events, Clock::time_point deadline) {
  for (;;) {
    pollfd entry{fd, events, 0};
    const int ready = poll(&entry, 1, RemainingMs(deadline));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return ready;
    return entry.revents;
  }
}

std::string SecondsText(std::chrono::milliseconds timeout) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", timeout.count() / 1000.0);
  return text;
}

// One address: a non-blocking connect, finished by poll within the deadline.
// Returns the socket, or -1 with `error` set.
int ConnectOne(const addrinfo& address, Clock::time_point deadline, std::string* error) {
  const int fd = socket(address.ai_family, address.ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, address.ai_protocol);
  if (fd < 0) {
    *error = std::strerror(errno);
    return -1;
  }
  if (connect(fd, address.ai_addr, address.ai_addrlen) == 0) return fd;
  if (errno == EINPROGRESS) {
    const int ready = WaitFor(fd, POLLOUT, deadline);
    int socket_error = 0;
    socklen_t length = sizeof socket_error;
    if (ready > 0 && getsockopt(fd, SOL_SOCKET, SO_ERROR, &socket_error, &length) == 0 && socket_error == 0) return fd;
    *error = ready == 0 ? "no answer (time-out)" : std::strerror(ready < 0 ? errno : socket_error);
  } else {
    *error = std::strerror(errno);
  }
  close(fd);
  return -1;
}

}  // namespace

std::string Excerpt(const std::string& text, size_t max_chars) {
  std::string shown = text.substr(0, max_chars);
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return "'" + shown + (text.size() > max_chars ? "...'" : "'");
}

StatusOr<LineClient> LineClient::Connect(const std::string& host, int port, std::chrono::milliseconds timeout) {
  const std::string peer = host + ":" + std::to_string(port);
  if (host.empty() || port < 1 || port > 65535)
    return Status::BadInput(peer + ": expected HOST:PORT with a port 1..65535");
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* addresses = nullptr;
  if (const int code = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &addresses); code != 0)
    return Status::BadInput(peer + ": cannot resolve '" + host + "': " + gai_strerror(code));
  const Clock::time_point deadline = Clock::now() + timeout;
  std::string error = "no address";
  int fd = -1;
  for (const addrinfo* address = addresses; address && fd < 0; address = address->ai_next)
    fd = ConnectOne(*address, deadline, &error);
  freeaddrinfo(addresses);
  if (fd < 0) return Status::IoError(peer + ": cannot connect within " + SecondsText(timeout) + ": " + error);
  return LineClient(fd, peer);
}

LineClient::LineClient(LineClient&& other) noexcept
    : fd_(other.fd_), peer_(std::move(other.peer_)), buffer_(std::move(other.buffer_)) {
  other.fd_ = -1;
}

LineClient& LineClient::operator=(LineClient&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) close(fd_);
    fd_ = other.fd_;
    peer_ = std::move(other.peer_);
    buffer_ = std::move(other.buffer_);
    other.fd_ = -1;
  }
  return *this;
}

LineClient::~LineClient() {
  if (fd_ >= 0) close(fd_);
}

Status LineClient::Send(const std::string& line) {
  const std::string bytes = line + "\r\n";
  const Clock::time_point deadline = Clock::now() + kSendTimeout;
  size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) && WaitFor(fd_, POLLOUT, deadline) > 0) continue;
    return Status::Failed(peer_ + ": cannot send " + Excerpt(line) + ": " +
                          (n < 0 && errno != EAGAIN ? std::strerror(errno) : "the peer does not read"));
  }
  return Status::Ok();
}

bool LineClient::TakeBufferedLine(std::string* line) {
  for (size_t end = buffer_.find('\n'); end != std::string::npos; end = buffer_.find('\n')) {
    std::string candidate = buffer_.substr(0, end);
    buffer_.erase(0, end + 1);
    const size_t first = candidate.find_first_not_of('\r');
    const size_t last = candidate.find_last_not_of('\r');
    if (first == std::string::npos) continue;  // an empty line
    *line = candidate.substr(first, last - first + 1);
    return true;
  }
  return false;
}

StatusOr<std::string> LineClient::ReadLine(std::chrono::milliseconds timeout) {
  const Clock::time_point deadline = Clock::now() + timeout;
  std::string line;
  while (!TakeBufferedLine(&line)) {
    if (buffer_.size() > kMaxLineBytes) {
      const std::string excerpt = Excerpt(buffer_);
      buffer_.clear();  // not a reply: not returned in pieces by later reads either
      return Status::Failed(peer_ + ": a reply line longer than " + std::to_string(kMaxLineBytes) +
                            " bytes: " + excerpt);
    }
    const int ready = WaitFor(fd_, POLLIN, deadline);
    if (ready == 0) return Status::Failed(peer_ + ": no reply within " + SecondsText(timeout));
    if (ready < 0) return Status::Failed(peer_ + ": waiting for a reply: " + std::strerror(errno));
    char chunk[1024];
    const ssize_t n = recv(fd_, chunk, sizeof chunk, 0);
    if (n == 0) return Status::Failed(peer_ + ": the connection was closed by the peer");
    if (n < 0 && errno != EINTR && errno != EAGAIN)
      return Status::Failed(peer_ + ": reading a reply: " + std::strerror(errno));
    if (n > 0) buffer_.append(chunk, static_cast<size_t>(n));
  }
  return line;
}

}  // namespace hexcal::workflow
