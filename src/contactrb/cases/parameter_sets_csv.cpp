// CSV files of parameter points: read_points_csv and points_csv_text (parameter_sets.hpp).
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <string_view>

#include "contactrb/cases/parameter_sets.hpp"
#include "contactrb/cases/parameter_sets_detail.hpp"
#include "contactrb/common/error.hpp"
#include "contactrb/common/input_file.hpp"
#include "contactrb/common/printable.hpp"

namespace contactrb::cases {

namespace {

struct Line {
  int number = 0;  // 1-based, counting every line of the file
  std::string_view text;
};

struct Field {
  std::string text;
  bool quoted = false;  // a quoted field is never a number when telling a header from data
};

bool is_blank(char c) { return c == ' ' || c == '\t'; }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

// The lines that hold points or the header: LF or CRLF ends a line; blank lines and comment
// lines ('#' as the first non-blank character) are dropped.
std::vector<Line> content_lines(std::string_view text) {
  std::vector<Line> lines;
  int number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string_view t = trimmed(line);
    if (!t.empty() && t.front() != '#') lines.push_back({number, t});
  }
  return lines;
}

// Reads a quoted field starting at line[pos] == '"'; "" stands for one quote. Returns the
// position after the closing quote.
std::size_t read_quoted(std::string_view line, std::size_t pos, std::string& out, const std::string& where) {
  for (++pos; pos < line.size(); ++pos) {
    if (line[pos] != '"') {
      out += line[pos];
    } else if (pos + 1 < line.size() && line[pos + 1] == '"') {
      out += '"';
      ++pos;
    } else {
      return pos + 1;
    }
  }
  throw Error(where + ": a quoted field has no closing quote");
}

std::vector<Field> split_fields(std::string_view line, const std::string& where) {
  std::vector<Field> fields;
  std::size_t pos = 0;
  while (true) {
    while (pos < line.size() && is_blank(line[pos])) ++pos;
    Field f;
    if (pos < line.size() && line[pos] == '"') {
      f.quoted = true;
      pos = read_quoted(line, pos, f.text, where);
      while (pos < line.size() && is_blank(line[pos])) ++pos;
      if (pos < line.size() && line[pos] != ',') {
        throw Error(where + ": text after the quoted field \"" + printable_line(f.text) + "\"");
      }
    } else {
      const std::size_t end = std::min(line.find(',', pos), line.size());
      f.text = std::string(trimmed(line.substr(pos, end - pos)));
      pos = end;
    }
    fields.push_back(std::move(f));
    if (pos >= line.size()) return fields;
    ++pos;  // the comma
  }
}

// The whole field as a double (a leading '+' allowed), or nothing.
std::optional<double> number_of(const std::string& text) {
  const char* first = text.data();
  const char* last = first + text.size();
  if (first != last && *first == '+') ++first;
  double v = 0.0;
  const auto r = std::from_chars(first, last, v);
  if (r.ec != std::errc() || r.ptr != last || first == last) return std::nullopt;
  return v;
}

bool is_data(const std::vector<Field>& fields) {
  for (const Field& f : fields) {
    if (f.quoted || !number_of(f.text)) return false;
  }
  return true;
}

std::string list_text(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
  return s;
}

// column -> parameter index, from a header that must name every parameter exactly once.
std::vector<int> header_columns(const std::vector<Field>& header, const ParameterBox& box, const std::string& where) {
  std::map<std::string, int> index;
  for (int k = 0; k < box.size(); ++k) index[box.names[static_cast<std::size_t>(k)]] = k;
  std::vector<int> column(header.size(), -1);
  std::vector<int> count(static_cast<std::size_t>(box.size()), 0);
  std::vector<std::string> unknown, repeated, missing;
  for (std::size_t c = 0; c < header.size(); ++c) {
    const auto it = index.find(header[c].text);
    if (it == index.end()) {
      unknown.push_back(printable_line(header[c].text));  // file content, echoed
    } else if (++count[static_cast<std::size_t>(it->second)] == 2) {
      repeated.push_back(printable_line(header[c].text));
    }
    if (it != index.end()) column[c] = it->second;
  }
  for (int k = 0; k < box.size(); ++k) {
    if (count[static_cast<std::size_t>(k)] == 0) missing.push_back(box.names[static_cast<std::size_t>(k)]);
  }
  if (unknown.empty() && repeated.empty() && missing.empty()) return column;
  std::string m = where + ": the header must name each parameter exactly once (" + list_text(box.names) + ")";
  if (!missing.empty()) m += "; missing: " + list_text(missing);
  if (!unknown.empty()) m += "; unknown: " + list_text(unknown);
  if (!repeated.empty()) m += "; repeated: " + list_text(repeated);
  bool some_number = false;
  for (const Field& f : header) some_number = some_number || (!f.quoted && number_of(f.text));
  if (some_number) m += " (the first line is read as a header because not all its fields are numbers)";
  throw Error(m);
}

Eigen::VectorXd read_point(const std::vector<Field>& fields, const std::vector<int>& column, const ParameterBox& box,
                           const std::string& where) {
  if (fields.size() != column.size()) {
    throw Error(where + ": " + std::to_string(fields.size()) + " values, expected " + std::to_string(box.size()) +
                " (" + list_text(box.names) + ")");
  }
  Eigen::VectorXd mu(box.size());
  for (std::size_t c = 0; c < fields.size(); ++c) {
    const int k = column[c];
    const std::optional<double> v = number_of(fields[c].text);
    if (!v) {
      throw Error(where + ": the value of parameter '" + box.names[static_cast<std::size_t>(k)] + "' ('" +
                  printable_line(fields[c].text) + "') is not a number");
    }
    if (!(*v >= box.min[k] && *v <= box.max[k])) throw Error(where + ": " + detail::value_error(box, k, *v));
    mu[k] = *v;
  }
  return mu;
}

// A name is quoted when reading it unquoted would change it or make the line data or a comment.
std::string header_field(const std::string& name) {
  const bool plain = name.find_first_of(",\"") == std::string::npos && trimmed(name) == name && name[0] != '#' &&
                     !number_of(name);
  if (plain) return name;
  std::string s = "\"";
  for (const char c : name) s += c == '"' ? std::string("\"\"") : std::string(1, c);
  return s + "\"";
}

}  // namespace

std::vector<Eigen::VectorXd> read_points_csv(const std::string& file, const ParameterBox& box) {
  const std::string path = printable_line(file);  // as shown in messages
  check_parameter_box(box, "points file '" + path + "'");
  const std::string text = read_text_input(file, "points file");
  const std::vector<Line> lines = content_lines(text);
  if (lines.empty()) throw Error(path + ": no point (the file holds no line other than blanks and comments)");

  std::vector<int> column(static_cast<std::size_t>(box.size()));
  for (int k = 0; k < box.size(); ++k) column[static_cast<std::size_t>(k)] = k;
  std::size_t first_data = 0;
  const std::vector<Field> first = split_fields(lines[0].text, path + ":" + std::to_string(lines[0].number));
  if (!is_data(first)) {
    column = header_columns(first, box, path + ":" + std::to_string(lines[0].number));
    first_data = 1;
  }
  if (first_data == lines.size()) throw Error(path + ": no point after the header");
  if (static_cast<long long>(lines.size() - first_data) > kMaxParameterSetSize) {
    throw Error(path + ": more than " + std::to_string(kMaxParameterSetSize) + " points");
  }

  std::vector<Eigen::VectorXd> points;
  points.reserve(lines.size() - first_data);
  for (std::size_t i = first_data; i < lines.size(); ++i) {
    const std::string where = path + ":" + std::to_string(lines[i].number);
    points.push_back(read_point(split_fields(lines[i].text, where), column, box, where));
  }
  if (const auto repeat = detail::first_repeat(points)) {
    const Line& a = lines[first_data + static_cast<std::size_t>(repeat->first)];
    const Line& b = lines[first_data + static_cast<std::size_t>(repeat->second)];
    throw Error(path + ":" + std::to_string(b.number) + ": the point repeats the one on line " +
                std::to_string(a.number));
  }
  return points;
}

std::string points_csv_text(const std::vector<Eigen::VectorXd>& points, const ParameterBox& box) {
  check_parameter_box(box, "points_csv_text");
  check_points(points, box, "points_csv_text");
  std::string s;
  // Appended piece by piece: "," + std::string draws a -Wrestrict false positive from g++ 12.
  for (std::size_t k = 0; k < box.names.size(); ++k) {
    if (k > 0) s += ',';
    s += header_field(box.names[k]);
  }
  s += '\n';
  for (const Eigen::VectorXd& mu : points) {
    for (int k = 0; k < box.size(); ++k) {
      if (k > 0) s += ',';
      s += detail::shortest(mu[k]);
    }
    s += '\n';
  }
  return s;
}

}  // namespace contactrb::cases
