// The energy-balance error of core/energies.hpp.
#include "afemp/energies.hpp"

#include <algorithm>
#include <cmath>

namespace afemp::core {

double energy_balance_error(const Energies& now, const Energies& initial, double max_kinetic) {
  const double e0 = initial.total();
  const double scale = std::max(std::abs(e0) + std::abs(now.external_work), max_kinetic);
  if (scale <= 0.0) return 0.0;
  return (now.total() - e0 - now.external_work) / scale;
}

}  // namespace afemp::core
