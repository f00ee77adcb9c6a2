#include "config.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace gpilot {

void ParamCheck::require(bool ok, const char* key, const std::string& why) const {
  if (!ok) throw ConfigError(path_ + "." + key + ": " + why);
}

void ParamCheck::choice(const char* key, const std::string& value, std::initializer_list<const char*> choices) const {
  std::string list;
  for (const char* c : choices) {
    if (value == c) return;
    list += (list.empty() ? "" : ", ") + std::string(c);
  }
  throw ConfigError(path_ + "." + key + ": '" + value + "' is not one of " + list);
}

ParamReader::ParamReader(const YAML::Node& node, std::string path) : node_(node), path_(std::move(path)) {
  if (node_ && !node_.IsNull() && !node_.IsMap())
    throw ConfigError(path_ + ": expected a map of keys, got a " + (node_.IsSequence() ? "list" : "value"));
}

YAML::Node ParamReader::child(const char* key) const {
  if (!node_ || !node_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  return node_[key];
}

std::string ParamReader::qualified(const char* key) const { return path_ + "." + key; }

void ParamReader::mark(const char* key) { seen_.emplace_back(key); }

double ParamReader::read_number(const char* key, double min, double max, bool integral) {
  const YAML::Node v = child(key);
  const std::string name = qualified(key);
  if (!v.IsScalar()) throw ConfigError(name + ": expected a number");
  double d = 0;
  try {
    d = v.as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError(name + ": '" + v.Scalar() + "' is not a number");
  }
  if (!std::isfinite(d)) throw ConfigError(name + ": must be finite, got " + v.Scalar());
  if (integral && d != std::floor(d)) throw ConfigError(name + ": must be a whole number, got " + v.Scalar());
  if (d < min || d > max)
    throw ConfigError(name + ": " + v.Scalar() + " is out of range [" + ParamWriter::format_number(min, integral) +
                      ", " + ParamWriter::format_number(max, integral) + "]");
  return d;
}

void ParamReader::operator()(const char* key, bool& value, const char*) {
  const YAML::Node v = child(key);
  if (!v) return;
  try {
    value = v.as<bool>();
  } catch (const YAML::Exception&) {
    throw ConfigError(qualified(key) + ": expected true or false");
  }
  mark(key);
}

void ParamReader::operator()(const char* key, std::string& value, const char*) {
  const YAML::Node v = child(key);
  if (!v) return;
  if (!v.IsScalar()) throw ConfigError(qualified(key) + ": expected a string");
  value = v.Scalar();
  mark(key);
}

void ParamReader::finish() const {
  if (!node_ || !node_.IsMap()) return;
  for (const auto& kv : node_) {
    // A list or map as a key ("? [a]: 1") has no name: yaml-cpp's as<string>() would throw past ConfigError.
    if (!kv.first.IsScalar()) throw ConfigError(path_ + ": a key that is not a name (a list or a map)");
    const std::string key = kv.first.as<std::string>();
    if (std::find(seen_.begin(), seen_.end(), key) == seen_.end())
      throw ConfigError(path_ + "." + key + ": unknown key (see deploy/config/default.yaml for the keys of '" +
                        path_ + "')");
  }
}

std::string ParamWriter::format_number(double v, bool integral) {
  char buf[64];
  if (integral) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
  } else {
    std::snprintf(buf, sizeof buf, "%.9g", v);
    std::string s(buf);
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // keep it a float in YAML
    return s;
  }
  return buf;
}

void ParamWriter::line(const char* key, const std::string& value, const char* doc, double min, double max) {
  std::string range;
  if (min > -1e300 || max < 1e300) {
    const bool integral = value.find_first_of(".eE") == std::string::npos;
    range = " [" + format_number(min, integral) + ", " + format_number(max, integral) + "]";
  }
  out_ += std::string(indent_, ' ') + key + ": " + value + "  # " + doc + range + "\n";
}

void ParamWriter::operator()(const char* key, bool& value, const char* doc) {
  out_ += std::string(indent_, ' ') + key + ": " + (value ? "true" : "false") + "  # " + doc + "\n";
}

void ParamWriter::operator()(const char* key, std::string& value, const char* doc) {
  YAML::Emitter e;
  e << YAML::DoubleQuoted << value;
  out_ += std::string(indent_, ' ') + key + ": " + e.c_str() + "  # " + doc + "\n";
}

Config::Config() : root_(YAML::NodeType::Map), origin_("<defaults>") {}

Config Config::from_string(const std::string& yaml, const std::string& origin) {
  Config c;
  c.origin_ = origin;
  try {
    c.root_ = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw ConfigError(origin + ": not valid YAML: " + e.what());
  }
  if (!c.root_ || c.root_.IsNull()) c.root_ = YAML::Node(YAML::NodeType::Map);
  if (!c.root_.IsMap()) throw ConfigError(origin + ": expected a map of sections at the top level");
  return c;
}

Config Config::from_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open config file");
  std::stringstream ss;
  ss << in.rdbuf();
  return from_string(ss.str(), path);
}

void Config::set(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("--set '" + assignment + "': expected section.key=value");
  const std::string path = assignment.substr(0, eq);
  const std::string value = assignment.substr(eq + 1);
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string p; std::getline(ss, p, '.');) {
    if (p.empty()) throw ConfigError("--set '" + assignment + "': empty name in '" + path + "'");
    parts.push_back(p);
  }
  if (parts.size() < 2) throw ConfigError("--set '" + assignment + "': expected section.key=value");
  YAML::Node parsed;
  try {
    parsed = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    throw ConfigError("--set " + path + ": bad value '" + value + "'");
  }
  // Walk with owned copies: yaml-cpp's operator[] on a Node reference would rebind, not assign.
  std::vector<YAML::Node> chain{root_};
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node next = chain.back()[parts[i]];
    if (!next || next.IsNull()) {
      chain.back()[parts[i]] = YAML::Node(YAML::NodeType::Map);
      next = chain.back()[parts[i]];
    }
    if (!next.IsMap()) throw ConfigError("--set " + path + ": '" + parts[i] + "' is not a section");
    chain.push_back(next);
  }
  chain.back()[parts.back()] = parsed;
}

std::vector<std::string> Config::section_names() const {
  std::vector<std::string> names;
  for (const auto& kv : root_) {
    if (!kv.first.IsScalar()) throw ConfigError(origin_ + ": a section name that is not a name (a list or a map)");
    names.push_back(kv.first.as<std::string>());
  }
  return names;
}

}  // namespace gpilot
