// Runs a user strength model (afemp/user_material.hpp) on a chunk of points: the solvers load
// each point's start state (start_increment of material.hpp) and history into structure-of-
// arrays scratch, the user's function is called once for the chunk, and the solvers finish
// each point (finish_increment: energy equation, EOS pressure, heating). The scratch lives
// for a whole batch sweep of one thread: nothing is allocated per point.
#pragma once

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/materials/material.hpp"

namespace afemp::core {

// Points per call of a user model: enough to amortise the call, few enough that the scratch
// stays in the L1/L2 cache (17 doubles per point plus the history).
inline constexpr std::size_t kUserChunk = 64;

class UserStrengthChunk {
 public:
  UserStrengthChunk(const Material& material, const UserStrength& model)
      : model_(*model.definition),
        parameters_(model.parameters),
        shear_modulus_(material.shear_modulus()),
        history_count_(model.history_count()),
        history_(history_count_ * kUserChunk) {}

  std::size_t history_count() const { return history_count_; }

  // Point j of the chunk: its state after the objective rotation (density at the end of the
  // increment), the start of its increment, and its history (history_count values).
  void load(std::size_t j, const PointState& point, const IncrementStart& in,
            const double* history) {
    const double de[6] = {in.de_dev.xx, in.de_dev.yy, in.de_dev.zz,
                          in.de_dev.yz, in.de_dev.xz, in.de_dev.xy};
    const double s[6] = {in.s_old.xx, in.s_old.yy, in.s_old.zz,
                         in.s_old.yz, in.s_old.xz, in.s_old.xy};
    for (int k = 0; k < 6; ++k) {
      strain_[k][j] = de[k];
      deviator_[k][j] = s[k];
    }
    plastic_strain_[j] = point.plastic_strain;
    temperature_[j] = point.temperature;
    pressure_[j] = in.p_old;
    density_[j] = point.density;
    for (std::size_t v = 0; v < history_count_; ++v) history_[v * kUserChunk + j] = history[v];
  }

  // One call of the user's update for points 0..count-1.
  void run(std::size_t count, double dt) {
    StrengthBatch b;
    b.count = count;
    b.dt = dt;
    b.shear_modulus = shear_modulus_;
    b.parameters = parameters_.data();
    for (int k = 0; k < 6; ++k) {
      b.strain_increment[k] = strain_[k];
      b.deviator[k] = deviator_[k];
    }
    b.plastic_strain = plastic_strain_;
    b.temperature = model_.reads_temperature ? temperature_ : nullptr;
    b.pressure = model_.reads_pressure ? pressure_ : nullptr;
    b.density = density_;
    std::fill(increment_, increment_ + count, 0.0);
    std::fill(flow_, flow_ + count, 0.0);
    b.plastic_strain_increment = increment_;
    b.flow_stress = flow_;
    // The batch's history is variable-major with stride count: close the gaps of a part chunk.
    if (count < kUserChunk)
      for (std::size_t v = 1; v < history_count_; ++v)
        std::copy_n(&history_[v * kUserChunk], count, &history_[v * count]);
    b.history = history_count_ > 0 ? history_.data() : nullptr;
    model_.update(b);
    if (count < kUserChunk)
      for (std::size_t v = history_count_; v-- > 1;)
        std::copy_backward(&history_[v * count], &history_[v * count + count],
                           &history_[v * kUserChunk + count]);
  }

  // Point j's results after run(): the deviator at the end and the strength result.
  SymTensor deviator(std::size_t j) const {
    return {deviator_[0][j], deviator_[1][j], deviator_[2][j],
            deviator_[3][j], deviator_[4][j], deviator_[5][j]};
  }
  DeviatoricResult result(std::size_t j) const { return {increment_[j], flow_[j]}; }
  void store_history(std::size_t j, double* history) const {
    for (std::size_t v = 0; v < history_count_; ++v) history[v] = history_[v * kUserChunk + j];
  }

 private:
  const UserStrengthDefinition& model_;
  const std::vector<double>& parameters_;
  double shear_modulus_;
  std::size_t history_count_;
  std::vector<double> history_;
  alignas(64) double strain_[6][kUserChunk];
  alignas(64) double deviator_[6][kUserChunk];
  double plastic_strain_[kUserChunk], temperature_[kUserChunk], pressure_[kUserChunk],
      density_[kUserChunk], increment_[kUserChunk], flow_[kUserChunk];
};

// What a solver's sweep holds for a batch of strength model Strength: the chunk for a user
// model, nothing for a built-in one (constructed from the same arguments).
struct NoUserChunk {
  template <class... Args>
  explicit NoUserChunk(const Args&...) {}
};
template <class Strength>
using UserChunkFor = std::conditional_t<is_user_strength<Strength>, UserStrengthChunk, NoUserChunk>;

// The initial history of a material's points, `count` values (0 where the model gives none).
inline void initial_history(const Material& material, double* history, std::size_t count) {
  std::fill(history, history + count, 0.0);
  if (const auto* u = std::get_if<UserStrength>(&material.strength))
    if (u->definition)
      std::copy_n(u->definition->initial_history.begin(),
                  std::min(count, u->definition->initial_history.size()), history);
}

}  // namespace afemp::core
