// SHA-256, the checksum of a job's result as the service sends it and meshctl checks it.
#pragma once

#include <string>
#include <string_view>

namespace meshd {

// Lower-case hex SHA-256 of `bytes`.
std::string sha256_hex(std::string_view bytes);

}  // namespace meshd
