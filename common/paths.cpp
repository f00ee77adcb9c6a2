#include "paths.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace gpilot {

namespace fs = std::filesystem;

std::string installed_data_dir(const std::string& exe_path) {
  std::error_code ec;
  const fs::path exe = fs::canonical(exe_path, ec);
  if (ec) return "";
  // The layout `cmake --install` writes: bin/ and share/gesture-pilot/ under one prefix (GPILOT_DATA_FROM_BIN,
  // from CMake's install dirs, is "../share/gesture-pilot").
  const fs::path dir = (exe.parent_path() / GPILOT_DATA_FROM_BIN).lexically_normal();
  return fs::is_directory(dir, ec) ? dir.string() : "";
}

std::string project_root() {
  if (const char* env = std::getenv("GPILOT_ROOT"); env && *env) return env;
  // Looked up once: the executable does not move while it runs.
  static const std::string installed = installed_data_dir("/proc/self/exe");
  if (!installed.empty()) return installed;
  return GPILOT_SOURCE_DIR;
}

std::string resolve_project_path(const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute() || fs::exists(path)) return path;
  return (fs::path(project_root()) / path).string();
}

}  // namespace gpilot
