// One YAML file, one section per stage. Each stage declares its parameters in a Params struct whose
// member initialisers are the paper's defaults and whose visit() names every key with its range and a
// one-line description; the readers below check the file against those declarations.
#pragma once

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace gpilot {

// A bad config file, key or value. The message names the key ("hands.lambda1: ...").
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The rules one key's range cannot say: a string that names one of a few choices, and keys that must agree
// (min below max). A Params struct states them in an optional member
//   void check(const ParamCheck& c) const { c.choice("backend", backend, {"sim", "mavlink", "none"}); ... }
// that runs each time the struct is read (Config::section, ParamReader::group), so validate_config, which
// reads every section before the bus starts, stops a process on them with the key named.
class ParamCheck {
 public:
  explicit ParamCheck(std::string path) : path_(std::move(path)) {}

  // Throws ConfigError "path.key: why" unless ok.
  void require(bool ok, const char* key, const std::string& why) const;
  // Throws ConfigError "path.key: 'value' is not one of a, b, c" unless value is one of choices.
  void choice(const char* key, const std::string& value, std::initializer_list<const char*> choices) const;

 private:
  std::string path_;
};

namespace detail {
template <class P, class = void>
struct HasCheck : std::false_type {};
template <class P>
struct HasCheck<P, std::void_t<decltype(std::declval<const P&>().check(std::declval<const ParamCheck&>()))>>
    : std::true_type {};
}  // namespace detail

// Runs params.check() when the struct has one; path is its section ("flight", "hands.skin.adapt").
template <class P>
void check_params(const P& params, const std::string& path) {
  if constexpr (detail::HasCheck<P>::value) params.check(ParamCheck(path));
}

// Reads one YAML map into a Params struct: keys present overwrite defaults, every value is range
// checked, and a key that the struct does not declare is an error.
class ParamReader {
 public:
  ParamReader(const YAML::Node& node, std::string path);

  template <class T>
  void operator()(const char* key, T& value, double min, double max, const char* doc);
  void operator()(const char* key, bool& value, const char* doc);
  void operator()(const char* key, std::string& value, const char* doc);

  template <class P>
  void group(const char* key, P& params) {
    ParamReader sub(child(key), qualified(key));
    params.visit(sub);
    sub.finish();
    check_params(params, qualified(key));
    mark(key);
  }

  // Throws ConfigError for every key in the map that visit() did not name.
  void finish() const;

 private:
  YAML::Node child(const char* key) const;
  std::string qualified(const char* key) const;
  void mark(const char* key);
  double read_number(const char* key, double min, double max, bool integral);

  YAML::Node node_;
  std::string path_;
  std::vector<std::string> seen_;
};

// Writes a Params struct's defaults as commented YAML (the form of deploy/config/default.yaml).
class ParamWriter {
 public:
  explicit ParamWriter(int indent) : indent_(indent) {}

  template <class T>
  void operator()(const char* key, T& value, double min, double max, const char* doc) {
    line(key, format_number(static_cast<double>(value), std::is_integral<T>::value), doc, min, max);
  }
  void operator()(const char* key, bool& value, const char* doc);
  void operator()(const char* key, std::string& value, const char* doc);

  template <class P>
  void group(const char* key, P& params) {
    out_ += std::string(indent_, ' ') + key + ":\n";
    ParamWriter sub(indent_ + 2);
    params.visit(sub);
    out_ += sub.str();
  }

  const std::string& str() const { return out_; }
  static std::string format_number(double v, bool integral);

 private:
  void line(const char* key, const std::string& value, const char* doc, double min, double max);
  int indent_;
  std::string out_;
};

template <class T>
void ParamReader::operator()(const char* key, T& value, double min, double max, const char*) {
  static_assert(std::is_arithmetic<T>::value, "numeric parameter");
  if (!child(key)) return;
  value = static_cast<T>(read_number(key, min, max, std::is_integral<T>::value));
  mark(key);
}

// The whole file: a YAML map of sections, plus --set overrides.
class Config {
 public:
  Config();  // empty: every section at its defaults
  static Config from_file(const std::string& path);  // throws ConfigError (missing file, bad YAML)
  static Config from_string(const std::string& yaml, const std::string& origin = "<string>");

  // "section.key=value" or "section.group.key=value"; the value is parsed as YAML.
  void set(const std::string& assignment);

  // The section's parameters: defaults overwritten by the file; throws ConfigError on a bad key or value.
  template <class P>
  P section(const char* name) const {
    P params;
    ParamReader reader(root_[name], name);
    params.visit(reader);
    reader.finish();
    check_params(params, name);
    return params;
  }

  std::vector<std::string> section_names() const;
  const std::string& origin() const { return origin_; }

 private:
  YAML::Node root_;
  std::string origin_;
};

}  // namespace gpilot
