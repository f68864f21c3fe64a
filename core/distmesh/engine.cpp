#include "core/distmesh/engine.h"

namespace meshd {

void Engine::move_points_until(const StepRule& rule, int first_iteration, int limit,
                               std::vector<StepResult>& steps) {
  Settling settling = rule.settling;
  for (int k = 0; k < limit; ++k) {
    steps.push_back(move_points());
    settling = rule.settle(settling, steps.back());
    if (rule.stops(steps.back(), first_iteration + k, settling)) return;
  }
}

}  // namespace meshd
