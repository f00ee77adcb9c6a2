#include "bus_key.hpp"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

#include <openssl/rand.h>
#include <openssl/sha.h>

namespace gpilot {
namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

uint32_t bus_key_id(const std::array<uint8_t, 32>& bytes) {
  uint8_t digest[SHA256_DIGEST_LENGTH];
  SHA256(bytes.data(), bytes.size(), digest);
  return (uint32_t{digest[0]} << 24) | (uint32_t{digest[1]} << 16) | (uint32_t{digest[2]} << 8) | digest[3];
}

BusKey load_bus_key(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw std::runtime_error("bus key " + path + ": " + std::strerror(errno) + " (make one with gpilot-keygen)");
  if (st.st_mode & (S_IRWXG | S_IRWXO))
  {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%03o", static_cast<unsigned>(st.st_mode & 0777));
    throw std::runtime_error("bus key " + path + " is open to group or others (mode " + mode + "): chmod 600 it");
  }
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw std::runtime_error("bus key " + path + ": cannot read");
  BusKey key;
  if (text.size() == key.bytes.size()) {
    std::memcpy(key.bytes.data(), text.data(), key.bytes.size());
  } else {
    std::string hex;
    for (char c : text)
      if (!std::isspace(static_cast<unsigned char>(c))) hex += c;
    if (hex.size() != 2 * key.bytes.size())
      throw std::runtime_error("bus key " + path + ": not a key (32 raw bytes or 64 hex digits; gpilot-keygen makes one)");
    for (size_t i = 0; i < key.bytes.size(); ++i) {
      const int hi = hex_digit(hex[2 * i]), lo = hex_digit(hex[2 * i + 1]);
      if (hi < 0 || lo < 0) throw std::runtime_error("bus key " + path + ": not hex digits");
      key.bytes[i] = static_cast<uint8_t>(hi * 16 + lo);
    }
  }
  key.id = bus_key_id(key.bytes);
  return key;
}

BusKey make_bus_key_file(const std::string& path) {
  BusKey key;
  if (RAND_bytes(key.bytes.data(), static_cast<int>(key.bytes.size())) != 1)
    throw std::runtime_error("no randomness for a bus key (OpenSSL RAND_bytes failed)");
  key.id = bus_key_id(key.bytes);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) throw std::runtime_error("bus key " + path + ": " + std::strerror(errno));
  static const char* digits = "0123456789abcdef";
  std::string hex;
  for (uint8_t b : key.bytes) {
    hex += digits[b >> 4];
    hex += digits[b & 15];
  }
  hex += '\n';
  const bool ok = ::write(fd, hex.data(), hex.size()) == static_cast<ssize_t>(hex.size());
  ::close(fd);
  if (!ok) throw std::runtime_error("bus key " + path + ": write failed");
  return key;
}

}  // namespace gpilot
