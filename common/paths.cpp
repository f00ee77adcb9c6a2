#include "paths.hpp"

#include <cstdlib>
#include <filesystem>

namespace gpilot {

std::string project_root() {
  if (const char* env = std::getenv("GPILOT_ROOT"); env && *env) return env;
  return GPILOT_SOURCE_DIR;
}

std::string resolve_project_path(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty() || fs::path(path).is_absolute() || fs::exists(path)) return path;
  return (fs::path(project_root()) / path).string();
}

}  // namespace gpilot
