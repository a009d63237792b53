// What hexcal prints reaches a terminal. Names come from files and devices (a
// robot's name, an image's, a controller's greeting) and may hold escape
// sequences that recolour, retitle or rewrite the terminal (issue 36), so for
// the lifetime of a TerminalEscaping every control byte written to std::cout
// or std::cerr but line feed and tab (and the progress bar's carriage return,
// on stderr) comes out as \xNN, in one place for every command.
//
//   TerminalEscaping escaping;                 // RunHexcal, around the parse
//   std::cout << "robot 'a\x1b[31m'";          // prints robot 'a\x1b[31m'
//
// --json output has no raw control bytes (JSON escapes them as \u001b).
#pragma once

#include <streambuf>

namespace hexcal::cli {

// Writes to `target`, each control byte as the four characters \xNN.
class EscapingBuffer : public std::streambuf {
 public:
  EscapingBuffer(std::streambuf* target, bool keep_carriage_return)
      : target_(target), keep_carriage_return_(keep_carriage_return) {}

 protected:
  int_type overflow(int_type c) override;
  std::streamsize xsputn(const char* text, std::streamsize count) override;
  int sync() override { return target_->pubsync(); }

 private:
  bool Put(unsigned char c);

  std::streambuf* target_;
  bool keep_carriage_return_;
};

// Puts EscapingBuffers in front of std::cout's and std::cerr's buffers;
// restores them when destroyed.
class TerminalEscaping {
 public:
  TerminalEscaping();
  ~TerminalEscaping();
  TerminalEscaping(const TerminalEscaping&) = delete;
  TerminalEscaping& operator=(const TerminalEscaping&) = delete;

 private:
  std::streambuf* out_target_;
  std::streambuf* err_target_;
  EscapingBuffer out_;
  EscapingBuffer err_;
};

}  // namespace hexcal::cli
