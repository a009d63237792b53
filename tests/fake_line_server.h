// A fake line-protocol server for client tests (devices/line_client.h):
// a thread serving canned replies on a loopback port.
//
//   FakeLineServer server([](const std::string& line) { return "HELLO ACK\r\n"; });
//   LineClient::Connect("127.0.0.1", server.port(), 1000ms);
#pragma once

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace hexcal::testing {

constexpr const char* kCloseConnection = "\x01" "close";  // no real reply starts with \x01

// Serves one connection at a time on 127.0.0.1 (an ephemeral port): every
// line received goes to `handler`, whose answer is sent as it is (raw bytes,
// terminators included; "" sends nothing; kCloseConnection closes).
class FakeLineServer {
 public:
  using Handler = std::function<std::string(const std::string& line)>;
  explicit FakeLineServer(Handler handler) : handler_(std::move(handler)) {
    listener_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    EXPECT_EQ(bind(listener_, reinterpret_cast<sockaddr*>(&address), length), 0);
    EXPECT_EQ(listen(listener_, 4), 0);
    getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length);
    port_ = ntohs(address.sin_port);
    thread_ = std::thread([this] { Serve(); });
  }
  ~FakeLineServer() {
    stop_ = true;
    thread_.join();
    close(listener_);
  }
  int port() const { return port_; }
  std::vector<std::string> Received() {
    std::lock_guard<std::mutex> hold(mutex_);
    return received_;
  }

 private:
  bool Readable(int fd) {
    pollfd entry{fd, POLLIN, 0};
    return poll(&entry, 1, 20) > 0;
  }
  void Serve() {
    while (!stop_) {
      if (!Readable(listener_)) continue;
      const int fd = accept(listener_, nullptr, nullptr);
      ServeConnection(fd);
      close(fd);
    }
  }
  void ServeConnection(int fd) {
    std::string buffer;
    while (!stop_) {
      if (!Readable(fd)) continue;
      char chunk[512];
      const ssize_t n = recv(fd, chunk, sizeof chunk, 0);
      if (n <= 0) return;
      buffer.append(chunk, static_cast<size_t>(n));
      for (size_t end = buffer.find('\n'); end != std::string::npos; end = buffer.find('\n')) {
        std::string line = buffer.substr(0, end);
        buffer.erase(0, end + 1);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        {
          std::lock_guard<std::mutex> hold(mutex_);
          received_.push_back(line);
        }
        const std::string reply = handler_(line);
        if (reply == kCloseConnection) return;
        if (!reply.empty()) send(fd, reply.data(), reply.size(), MSG_NOSIGNAL);
      }
    }
  }

  Handler handler_;
  int listener_ = -1, port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  std::mutex mutex_;
  std::vector<std::string> received_;
};

}  // namespace hexcal::testing
