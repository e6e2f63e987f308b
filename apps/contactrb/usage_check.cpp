#include "usage_check.hpp"

#include <algorithm>
#include <string_view>

namespace contactrb::app {

namespace {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string suggestion(const std::string& word, const std::vector<std::string>& known) {
  const std::string near = nearest_name(word, known);
  return near.empty() ? std::string() : " (did you mean '" + near + "'?)";
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App* s) { return !s->get_name().empty(); })) {
    names.push_back(sub->get_name());
  }
  return names;
}

// Long option names of `app` and of its option groups (nameless subcommands).
void long_option_names(const CLI::App& app, std::vector<std::string>& names) {
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
  }
  for (const CLI::App* group : app.get_subcommands([](const CLI::App* s) { return s->get_name().empty(); })) {
    long_option_names(*group, names);
  }
}

}  // namespace

std::string nearest_name(const std::string& word, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(1, word.size() / 3) + 1;
  for (const std::string& k : known) {
    const std::size_t d = k.starts_with(word) && word.size() >= 3 ? 0 : edit_distance(word, k);
    if (d < best_distance) {
      best_distance = d;
      best = k;
    }
  }
  return best;
}

void check_names(const CLI::App& app, int argc, char** argv) {
  if (argc < 2) return;
  const std::string command = argv[1];
  if (command.empty() || command.front() == '-') return;
  const std::vector<std::string> commands = subcommand_names(app);
  if (std::find(commands.begin(), commands.end(), command) == commands.end()) {
    std::string list;
    for (const std::string& c : commands) list += (list.empty() ? "" : ", ") + c;
    throw CLI::ExtrasError("unknown command '" + command + "'" + suggestion(command, commands) + "; the commands are " +
                               list,
                           static_cast<int>(CLI::ExitCodes::ExtrasError));
  }
  const CLI::App* sub = app.get_subcommand(command);
  std::vector<std::string> options{"--help"};
  long_option_names(app, options);
  long_option_names(*sub, options);
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg(argv[i]);
    if (arg == "--") break;
    if (!arg.starts_with("--")) continue;
    const std::string name(arg.substr(0, arg.find('=')));
    if (std::find(options.begin(), options.end(), name) != options.end()) continue;
    throw CLI::ExtrasError("unknown option '" + name + "' of `contactrb " + command + "`" + suggestion(name, options),
                           static_cast<int>(CLI::ExitCodes::ExtrasError));
  }
}

}  // namespace contactrb::app
