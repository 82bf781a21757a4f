#include "args.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace ffdkit::cli {

namespace {

const OptionSpec* findSpec(const std::vector<OptionSpec>& specs, const std::string& name, bool isShort) {
  for (const auto& spec : specs) {
    if (isShort ? (spec.shortName != '\0' && name.size() == 1 && name[0] == spec.shortName) : spec.name == name)
      return &spec;
  }
  return nullptr;
}

std::string knownOptions(const std::vector<OptionSpec>& specs) {
  std::string list;
  for (const auto& spec : specs) list += (list.empty() ? "--" : ", --") + spec.name;
  return list;
}

}  // namespace

Args::Args(const std::vector<OptionSpec>& specs, const std::vector<std::string>& argv) {
  bool optionsEnded = false;
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& arg = argv[i];
    if (optionsEnded || arg.size() < 2 || arg[0] != '-') {
      positional_.push_back(arg);
      continue;
    }
    if (arg == "--") {
      optionsEnded = true;
      continue;
    }
    const bool isShort = arg[1] != '-';
    std::string name = isShort ? arg.substr(1) : arg.substr(2);
    std::optional<std::string> inlineValue;
    if (const auto eq = name.find('='); !isShort && eq != std::string::npos) {
      inlineValue = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const OptionSpec* spec = findSpec(specs, name, isShort);
    if (spec == nullptr) throw UsageError("unknown option '" + arg + "' (known: " + knownOptions(specs) + ")");
    const std::string display = "--" + spec->name;
    if (!spec->repeatable && values_.count(spec->name) != 0) throw UsageError(display + " given twice");
    if (spec->valueName.empty()) {
      if (inlineValue) throw UsageError(display + " takes no value");
      values_[spec->name].emplace_back();
      continue;
    }
    if (!inlineValue) {
      if (i + 1 >= argv.size()) throw UsageError(display + " needs a value: " + display + " " + spec->valueName);
      inlineValue = argv[++i];
    }
    values_[spec->name].push_back(*inlineValue);
  }
}

std::optional<std::string> Args::value(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second.back();
}

std::vector<std::string> Args::values(const std::string& name) const {
  auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

std::string optionHelp(const std::vector<OptionSpec>& specs) {
  std::string text;
  for (const auto& spec : specs) {
    std::string left = spec.shortName != '\0' ? std::string("-") + spec.shortName + ", " : "    ";
    left += "--" + spec.name;
    if (!spec.valueName.empty()) left += " " + spec.valueName;
    char line[512];
    std::snprintf(line, sizeof line, "  %-28s %s%s\n", left.c_str(), spec.help.c_str(),
                  spec.repeatable ? " (repeatable)" : "");
    text += line;
  }
  return text;
}

void parseSize(const std::string& text, const std::string& option, int& width, int& height) {
  int w = 0;
  int h = 0;
  char tail = '\0';
  if (std::sscanf(text.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
    throw UsageError(option + " takes WIDTHxHEIGHT with 1..16384 pixels per side, e.g. 800x600; got '" + text + "'");
  width = w;
  height = h;
}

double parseNumber(const std::string& text, const std::string& what) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value))
    throw UsageError(what + " must be a finite number, got '" + text + "'");
  return value;
}

}  // namespace ffdkit::cli
