#include "contactrb/offline/snapshot_parts.hpp"

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>

#include "contactrb/common/error.hpp"

namespace contactrb::offline {

namespace {

// Digits only, no sign, no blanks (std::stoi would take " 2" and "2x").
std::optional<long long> whole_number(const std::string& s) {
  if (s.empty() || s.size() > 9) return std::nullopt;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  return std::stoll(s);
}

std::string part_text(SnapshotPart p) { return std::to_string(p.k) + "/" + std::to_string(p.count); }

void mix(std::uint64_t& h, const void* data, std::size_t bytes) {
  const auto* c = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    h ^= c[i];
    h *= 1099511628211ULL;
  }
}

// The fields every part of one run shares, as text: the first that differs is named.
std::vector<std::pair<std::string, std::string>> run_fields(const io::SnapshotSet& s, const PartTag& tag) {
  std::ostringstream params;
  params.precision(17);
  for (const io::SnapshotParameter& p : s.parameters) {
    params << p.name << "|" << p.kind << "|" << p.units << "|" << p.min << "|" << p.max << ";";
  }
  std::ostringstream kacanov;
  kacanov.precision(17);
  kacanov << "alpha " << s.kacanov_alpha << ", tolerance " << s.kacanov_tolerance << ", max iterations "
          << s.kacanov_max_iterations;
  std::ostringstream values;
  values << tag.total << " values, hash " << std::hex << tag.values;
  return {{"case", s.case_kind + ":" + s.case_name + "\n" + s.case_spec},
          {"mesh level", std::to_string(s.level)},
          {"dimension", std::to_string(s.dimension)},
          {"parameters", params.str()},
          {"HF solver", s.solver},
          {"Kacanov settings", kacanov.str()},
          {"parameter set", tag.set},
          {"number of parts", std::to_string(tag.part.count)},
          {"parameter values", values.str()}};
}

// The discretization of a part, empty when none of its solvers was built.
std::string discretization_text(const io::SnapshotSet& s) {
  if (s.num_dofs == 0) return "";
  std::ostringstream os;
  os << s.constraint << "|" << s.num_dofs;
  for (const std::vector<int>* v : {&s.free_dofs, &s.contact_dofs, &s.slave, &s.master}) {
    os << "|";
    for (int x : *v) os << x << ",";
  }
  return os.str();
}

}  // namespace

SnapshotPart parse_snapshot_part(const std::string& text, const std::string& flag) {
  const auto slash = text.find('/');
  const std::string usage = flag + " '" + text + "': expected k/K, part k of K with 1 <= k <= K (e.g. 2/4)";
  require(slash != std::string::npos, usage);
  const auto k = whole_number(text.substr(0, slash));
  const auto count = whole_number(text.substr(slash + 1));
  require(k && count && *k >= 1 && *k <= *count, usage);
  return {static_cast<int>(*k), static_cast<int>(*count)};
}

std::vector<std::size_t> part_indices(std::size_t n, SnapshotPart part) {
  std::vector<std::size_t> out;
  for (std::size_t i = static_cast<std::size_t>(part.k - 1); i < n; i += static_cast<std::size_t>(part.count)) {
    out.push_back(i);
  }
  return out;
}

std::string part_tag_text(const PartTag& tag) {
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016" PRIx64, tag.values);
  return tag.set + " [part " + part_text(tag.part) + " of " + std::to_string(tag.total) + " values, " + hash + "]";
}

std::optional<PartTag> parse_part_tag(const std::string& set_name) {
  const std::string open = " [part ";
  const auto at = set_name.rfind(open);
  if (at == std::string::npos || set_name.back() != ']') return std::nullopt;
  // "k/K of n values, hhhhhhhhhhhhhhhh"
  const std::string inner = set_name.substr(at + open.size(), set_name.size() - at - open.size() - 1);
  const auto of = inner.find(" of ");
  const auto comma = inner.find(" values, ");
  if (of == std::string::npos || comma == std::string::npos || comma < of) return std::nullopt;
  PartTag tag;
  tag.set = set_name.substr(0, at);
  try {
    tag.part = parse_snapshot_part(inner.substr(0, of));
  } catch (const Error&) {
    return std::nullopt;
  }
  const auto total = whole_number(inner.substr(of + 4, comma - of - 4));
  const std::string hex = inner.substr(comma + 9);
  if (!total || hex.size() != 16 || hex.find_first_not_of("0123456789abcdef") != std::string::npos) return std::nullopt;
  tag.total = static_cast<std::size_t>(*total);
  tag.values = std::strtoull(hex.c_str(), nullptr, 16);
  if (tag.part.count > static_cast<long long>(tag.total)) return std::nullopt;
  return tag;
}

std::uint64_t values_hash(const std::vector<cases::Mu>& mu) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const cases::Mu& m : mu) {
    const std::int64_t p = m.size();
    mix(h, &p, sizeof p);
    mix(h, m.data(), sizeof(double) * static_cast<std::size_t>(m.size()));
  }
  return h;
}

void restrict_to_part(SnapshotRequest& request, SnapshotPart part) {
  const std::size_t n = request.mu.size();
  require(static_cast<std::size_t>(part.count) <= n, "--part " + part_text(part) + ": the set '" + request.set_name +
                                                         "' has " + std::to_string(n) + " values, fewer than " +
                                                         std::to_string(part.count) + " parts (a part would be empty)");
  PartTag tag{request.set_name, part, n, values_hash(request.mu)};
  std::vector<cases::Mu> mine;
  for (std::size_t i : part_indices(n, part)) mine.push_back(request.mu[i]);
  request.mu = std::move(mine);
  request.set_name = part_tag_text(tag);
}

io::SnapshotSet merge_snapshot_parts(const std::vector<PartFile>& parts) {
  require(!parts.empty(), "merge: no part given");
  std::vector<PartTag> tags;
  for (const PartFile& f : parts) {
    const std::optional<PartTag> tag = parse_part_tag(f.set.set_name);
    require(tag.has_value(), f.path + " is not a part of a snapshot set (its set is '" + f.set.set_name +
                                 "'; parts are written by `contactrb snapshots --part k/K`)");
    tags.push_back(*tag);
  }
  // One run: the first part's fields, and its discretization (the first part that has one).
  const auto reference = run_fields(parts[0].set, tags[0]);
  std::size_t with_layout = parts.size();
  for (std::size_t j = 0; j < parts.size(); ++j) {
    const auto fields = run_fields(parts[j].set, tags[j]);
    for (std::size_t f = 0; f < fields.size(); ++f) {
      require(fields[f].second == reference[f].second,
              parts[j].path + " and " + parts[0].path + " are parts of different runs: their " + fields[f].first +
                  " differ" + (f >= 4 ? " ('" + fields[f].second + "' and '" + reference[f].second + "')" : ""));
    }
    if (discretization_text(parts[j].set).empty()) continue;
    if (with_layout == parts.size()) {
      with_layout = j;
    } else {
      require(discretization_text(parts[j].set) == discretization_text(parts[with_layout].set),
              parts[j].path + " and " + parts[with_layout].path +
                  " are parts of different runs: their HF discretizations (DOF map, contact chains or constraint) differ");
    }
  }
  const PartTag& run = tags[0];
  // Each part once.
  std::map<int, std::size_t> given;  // k -> index in parts
  for (std::size_t j = 0; j < parts.size(); ++j) {
    const auto [it, inserted] = given.emplace(tags[j].part.k, j);
    require(inserted, "part " + part_text(tags[j].part) + " is given twice: " + parts[it->second].path + " and " +
                          parts[j].path);
  }
  std::vector<std::string> missing;
  for (int k = 1; k <= run.part.count; ++k) {
    if (given.count(k) == 0) missing.push_back(part_text({k, run.part.count}));
  }
  if (!missing.empty()) {
    std::string list;
    for (const std::string& m : missing) list += (list.empty() ? "" : ", ") + m;
    throw Error(std::string(missing.size() == 1 ? "part " : "parts ") + list + (missing.size() == 1 ? " is" : " are") +
                " missing (" + std::to_string(parts.size()) + " of " + std::to_string(run.part.count) +
                " parts given, of the set '" + run.set + "')");
  }
  // Interleave: snapshot j of part k is value k - 1 + j K.
  io::SnapshotSet out = parts[with_layout == parts.size() ? 0 : with_layout].set;
  out.set_name = run.set;
  out.snapshots.assign(run.total, io::Snapshot{});
  for (std::size_t j = 0; j < parts.size(); ++j) {
    const std::vector<std::size_t> indices = part_indices(run.total, tags[j].part);
    require(parts[j].set.snapshots.size() == indices.size(),
            parts[j].path + " (part " + part_text(tags[j].part) + ") holds " +
                std::to_string(parts[j].set.snapshots.size()) + " values; part " + part_text(tags[j].part) + " of " +
                std::to_string(run.total) + " values has " + std::to_string(indices.size()));
    for (std::size_t i = 0; i < indices.size(); ++i) out.snapshots[indices[i]] = parts[j].set.snapshots[i];
  }
  std::vector<cases::Mu> mu;
  for (const io::Snapshot& s : out.snapshots) mu.push_back(s.mu);
  require(values_hash(mu) == run.values, "the values of the parts, in part order, are not the values of the run they "
                                         "name (hash mismatch): a part was edited or comes from another run");
  return out;
}

void refuse_snapshot_part(const io::SnapshotSet& set, const std::string& path) {
  const std::optional<PartTag> tag = parse_part_tag(set.set_name);
  require(!tag.has_value(), path + " is part " + (tag ? part_text(tag->part) : "") +
                                " of a snapshot set, not a whole set: merge the parts first (`contactrb merge`)");
}

}  // namespace contactrb::offline
