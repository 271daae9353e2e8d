#pragma once
/// The one error type for bad user input (scene, CSV, command line). Carries where the
/// problem is so the message can name file, line and key; main() prints it and exits 2.
#include <sstream>
#include <stdexcept>
#include <string>

namespace gpudem {

class InputError : public std::runtime_error {
 public:
  /// `file` and `key` may be empty; `line` is 1-based, 0 when unknown.
  InputError(std::string file, int line, std::string key, const std::string& what)
      : std::runtime_error(compose(file, line, key, what)),
        file_(std::move(file)),
        line_(line),
        key_(std::move(key)) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }

  /// "file:line: key 'key': what", each part left out when empty (line when 0): how errors and
  /// warnings about the input name their place.
  static std::string compose(const std::string& file, int line, const std::string& key,
                             const std::string& what) {
    std::string s;
    if (!file.empty()) s += file;
    if (line > 0) s += ":" + std::to_string(line);
    if (!s.empty()) s += ": ";
    if (!key.empty()) s += "key '" + key + "': ";
    return s + what;
  }

 private:
  std::string file_;
  int line_;
  std::string key_;
};

/// `x` to 4 significant digits, as messages about input quote measured values.
inline std::string four_digits(double x) {
  std::ostringstream s;
  s.precision(4);
  s << x;
  return s.str();
}

}  // namespace gpudem
