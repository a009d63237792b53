#include "ui/text_wrap.h"

namespace hexcal::ui {
namespace {

constexpr QChar kZeroWidthSpace(0x200B);

QString BreakWord(const QString& word) {
  if (word.size() <= kLongestUnbroken) return word;
  QString out;
  int unbroken = 0;
  for (const QChar c : word) {
    out += c;
    const bool after = c == '/' || c == '_' || c == '-' || c == '.';
    if (after || ++unbroken >= kLongestUnbroken) {
      out += kZeroWidthSpace;
      unbroken = 0;
    }
  }
  return out;
}

}  // namespace

QString Breakable(const QString& text) {
  QString out, word;
  for (const QChar c : text) {
    if (c.isSpace()) {
      out += BreakWord(word) + c;
      word.clear();
    } else {
      word += c;
    }
  }
  return out + BreakWord(word);
}

}  // namespace hexcal::ui
