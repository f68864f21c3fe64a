// SHA-256, the checksum of a job's result as the service sends it and meshctl checks it.
#pragma once

#include <memory>
#include <string>
#include <string_view>

struct evp_md_ctx_st;

namespace meshd {

// Lower-case hex SHA-256 of `bytes`.
std::string sha256_hex(std::string_view bytes);

// SHA-256 over bytes that arrive in pieces (a client hashes each chunk as it comes, so the
// check overlaps the transfer). Throws Error(kInternal) if the library fails.
class Sha256 {
 public:
  Sha256();
  void update(std::string_view bytes);
  // Lower-case hex digest of everything so far; more may be added after.
  std::string hex() const;

 private:
  struct Free {
    void operator()(evp_md_ctx_st* context) const;
  };
  std::unique_ptr<evp_md_ctx_st, Free> context_;
};

}  // namespace meshd
