// The bus key: 32 secret bytes shared by every process of one deployment (drone and ground station), kept in
// a file only its owner can read. Its id (the first 4 bytes of SHA-256 over it) names it in signatures, so
// two keys can be accepted while a new one is rolled out.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace gpilot {

struct BusKey {
  std::array<uint8_t, 32> bytes{};
  uint32_t id = 0;
};

// Reads a key file: 32 raw bytes, or 64 hex digits (whitespace around them ignored). Throws
// std::runtime_error naming the file when it is missing, readable by group or others, or not a key.
BusKey load_bus_key(const std::string& path);

// A new random key (OpenSSL's RAND_bytes), written with mode 0600 as 64 hex digits and a newline. Refuses to
// overwrite an existing file. Throws std::runtime_error.
BusKey make_bus_key_file(const std::string& path);

uint32_t bus_key_id(const std::array<uint8_t, 32>& bytes);

}  // namespace gpilot
