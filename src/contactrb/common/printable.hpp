#pragma once
// Text from the user (paths, batch lines, file contents) echoed into messages: a control
// character could move the cursor or clear the terminal (ESC sequences), and bytes that are
// not UTF-8 break JSON output. printable() makes such text safe to print.
#include <string>

namespace contactrb {

// `text` with every control character (C0 but newline, DEL, C1) and every byte that is not
// part of a valid UTF-8 sequence written as \xNN; printable ASCII and valid UTF-8 characters
// (accented letters in a path) are kept as they are. A backslash stays a backslash: the
// result is for reading, not for parsing back.
std::string printable(const std::string& text);

// printable() that also escapes newlines: for text that must stay on one line.
std::string printable_line(const std::string& text);

}  // namespace contactrb
