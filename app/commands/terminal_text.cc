#include "app/commands/terminal_text.h"

#include <cstdio>
#include <iostream>

namespace hexcal::cli {

EscapingBuffer::int_type EscapingBuffer::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
  return Put(static_cast<unsigned char>(traits_type::to_char_type(c))) ? c : traits_type::eof();
}

std::streamsize EscapingBuffer::xsputn(const char* text, std::streamsize count) {
  for (std::streamsize i = 0; i < count; ++i)
    if (!Put(static_cast<unsigned char>(text[i]))) return i;
  return count;
}

// Bytes 0x80 and above pass: they are UTF-8 (or Latin-1), not commands.
bool EscapingBuffer::Put(unsigned char c) {
  const bool kept = c == '\n' || c == '\t' || (c == '\r' && keep_carriage_return_);
  if ((c >= 0x20 && c != 0x7f) || kept)
    return !traits_type::eq_int_type(target_->sputc(static_cast<char>(c)), traits_type::eof());
  char escaped[8];
  std::snprintf(escaped, sizeof(escaped), "\\x%02x", c);
  return target_->sputn(escaped, 4) == 4;
}

TerminalEscaping::TerminalEscaping()
    : out_target_(std::cout.rdbuf()),
      err_target_(std::cerr.rdbuf()),
      out_(out_target_, false),
      err_(err_target_, true) {
  std::cout.rdbuf(&out_);
  std::cerr.rdbuf(&err_);
}

TerminalEscaping::~TerminalEscaping() {
  std::cout.flush();
  std::cerr.flush();
  std::cout.rdbuf(out_target_);
  std::cerr.rdbuf(err_target_);
}

}  // namespace hexcal::cli
