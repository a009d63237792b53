// Text put into hexcal's HTML pages (the session report and its sections):
// the one escape of <, > and &, so that a file name or message shows as text.
//
//   html += "<td>" + HtmlEscape(image) + "</td>";
#pragma once

#include <string>

namespace hexcal::workflow {

inline std::string HtmlEscape(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    if (c == '<')
      escaped += "&lt;";
    else if (c == '>')
      escaped += "&gt;";
    else if (c == '&')
      escaped += "&amp;";
    else
      escaped += c;
  }
  return escaped;
}

}  // namespace hexcal::workflow
