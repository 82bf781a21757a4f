#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ffdkit::cli {

/// A command line the user got wrong (unknown option, missing or malformed argument): exit 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One option of a subcommand. `valueName` empty: a flag; otherwise the option takes a value
/// (`--size 800x600` or `--size=800x600`).
struct OptionSpec {
  std::string name;       ///< long name without dashes, e.g. "size"
  char shortName = '\0';  ///< e.g. 'o' for -o; '\0' for none
  std::string valueName;  ///< e.g. "WxH"; empty for a flag
  std::string help;       ///< one line
  bool repeatable = false;
};

/// The parsed command line of one subcommand.
class Args {
 public:
  /// @throws UsageError naming the unknown option or the option whose value is missing.
  Args(const std::vector<OptionSpec>& specs, const std::vector<std::string>& argv);

  bool flag(const std::string& name) const { return values_.count(name) != 0; }
  std::optional<std::string> value(const std::string& name) const;
  std::vector<std::string> values(const std::string& name) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::map<std::string, std::vector<std::string>> values_;
  std::vector<std::string> positional_;
};

/// The option list of a help text, one option a line.
std::string optionHelp(const std::vector<OptionSpec>& specs);

/// Parses "WIDTHxHEIGHT" (each 1..16384). @throws UsageError naming `option`.
void parseSize(const std::string& text, const std::string& option, int& width, int& height);

/// Parses a finite number. @throws UsageError naming `what`.
double parseNumber(const std::string& text, const std::string& what);

}  // namespace ffdkit::cli
