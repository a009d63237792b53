// Text for a word-wrapped label that may quote a path or a file name: a
// label's narrowest width is its longest word, so an unbroken 90-character
// folder name would make the whole window wider than the screen (issue 35).
// Breakable() lets such a word break after '/', '_', '-' and '.' and at
// least every kLongestUnbroken characters (a zero-width space, U+200B, which
// shows nothing); shorter words are left exactly as they are.
//
//   status->setText(Breakable("kept in " + folder));
#pragma once

#include <QString>

namespace hexcal::ui {

constexpr int kLongestUnbroken = 24;

QString Breakable(const QString& text);

}  // namespace hexcal::ui
