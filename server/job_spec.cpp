#include "server/job_spec.h"

namespace meshd {

const char* backend_name(Backend backend) {
  switch (backend) {
    case Backend::kAuto:
      return "auto";
    case Backend::kGpu:
      return "gpu";
    case Backend::kCpu:
      return "cpu";
  }
  return "unknown";
}

}  // namespace meshd
