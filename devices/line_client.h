// A TCP client of a line-based text protocol (LinuxCNC's linuxcncrsh,
// devices/linuxcnc_controller.h): connect with a time-out, send a line, read
// the next non-empty line with a time-out. POSIX sockets, blocking only in
// poll(), so that a machine that stops answering is an error naming the wait,
// never a hang.
//
//   StatusOr<LineClient> client = LineClient::Connect("127.0.0.1", 5007, 5000ms);
//   if (Status s = client->Send("hello EMC hexcal 1.0"); !s.ok()) ...;
//   StatusOr<std::string> reply = client->ReadLine(2000ms);  // "HELLO ACK EMCNETSVR 1.1"
//
// Lines end with "\n"; a "\r" on either side of a line is dropped, because
// linuxcncrsh ends its acknowledgements "\n\r" and its replies "\r\n". Empty
// lines are skipped (a NAK is followed by one). Messages quote at most
// kReplyExcerptChars of a reply (Excerpt), whatever the server sends.
#pragma once

#include <chrono>
#include <string>

#include "core/status.h"

namespace hexcal::workflow {

// Longest line accepted: far above any linuxcncrsh reply, small enough that a
// server sending garbage without newlines is refused at once.
constexpr size_t kMaxLineBytes = 4096;
// How much of a reply an error message quotes.
constexpr size_t kReplyExcerptChars = 80;

// `text` cut to `max_chars` with "..." and control characters shown as '?',
// quoted: for messages about a reply.
std::string Excerpt(const std::string& text, size_t max_chars = kReplyExcerptChars);

class LineClient {
 public:
  // Connects to HOST:PORT (a name or an address), waiting at most `timeout`.
  // Errors name the peer ("127.0.0.1:5007") and the cause (refused, no such
  // host, time-out).
  static StatusOr<LineClient> Connect(const std::string& host, int port, std::chrono::milliseconds timeout);

  // A connected stream socket already open (one end of a socketpair to a
  // child process, say); the client closes it. `peer` names it in messages.
  static LineClient Adopt(int fd, std::string peer) { return LineClient(fd, std::move(peer)); }

  LineClient(LineClient&& other) noexcept;
  LineClient& operator=(LineClient&& other) noexcept;
  LineClient(const LineClient&) = delete;
  LineClient& operator=(const LineClient&) = delete;
  ~LineClient();

  // Sends `line` followed by "\r\n". Errors: the peer closed, a send failed.
  Status Send(const std::string& line);
  // The next non-empty line without its terminator. Errors (failed kind): no
  // line within `timeout`, the peer closed the connection, a line longer than
  // kMaxLineBytes.
  StatusOr<std::string> ReadLine(std::chrono::milliseconds timeout);
  // "127.0.0.1:5007": for messages.
  const std::string& peer() const { return peer_; }

 private:
  LineClient(int fd, std::string peer) : fd_(fd), peer_(std::move(peer)) {}
  // Moves the first complete non-empty line of buffer_ to `line`; false if none.
  bool TakeBufferedLine(std::string* line);

  int fd_ = -1;
  std::string peer_;
  std::string buffer_;  // received bytes not yet returned as lines
};

}  // namespace hexcal::workflow
