// SPDX-License-Identifier: MIT
// The colour states set (format 1.10) and its fade (state_machine.h,
// MachineColourJob): plain float arithmetic in a fixed order.
#include "machine_colour.h"

#include <cmath>

namespace posemorph {
namespace detail {
namespace {

// The body parts a state can set (a rig without parts has none).
std::uint32_t BodyParts(const Rig& rig) { return rig.part_count() > 1 ? rig.part_count() : 0; }

// A component read from caller bytes: in [0, 1], else 1 (as drawn).
float Component(float v) { return v >= 0 && v <= 1 ? v : 1.0f; }

// The layer's state as the step would read it: its own, or (outside the
// layer: bytes never stepped) its initial one.
const MachineStateView& StateOf(const Rig& rig, const MachineInstance& m, std::size_t l) {
  const MachineLayerView& layer = rig.machine_layers()[l];
  const std::uint32_t s = m.state[l];
  const bool inside = s >= layer.first_state && s < layer.first_state + layer.state_count;
  return rig.machine_states()[inside ? s : layer.initial];
}

// The product over the layers of their states' colours and part opacities.
void Target(const Rig& rig, const MachineInstance& m, float colour[4], float* parts) {
  const std::uint32_t P = BodyParts(rig);
  for (int c = 0; c < 4; ++c) colour[c] = 1;
  for (std::uint32_t p = 0; p < P; ++p) parts[p] = 1;
  for (std::size_t l = 0; l < rig.machine_layers().size; ++l) {
    const MachineStateView& s = StateOf(rig, m, l);
    for (int c = 0; c < 4; ++c) colour[c] *= s.colour[c];
    for (const MachinePartOpacityView& o : s.part_opacities)
      if (o.part < P) parts[o.part] *= o.opacity;
  }
}

// How far the fade has come, in [0, 1] (a finished or nonsensical fade: 1).
float Progress(const MachineInstance& m) {
  const double e = m.fade_elapsed, d = m.fade_duration;
  if (!(d > 0) || !(e < d) || !std::isfinite(d)) return 1;
  return e > 0 ? float(e / d) : 0.0f;
}

}  // namespace

void ShownColour(const Rig& rig, const MachineInstance& m, float colour[4], float* parts) {
  const std::uint32_t P = BodyParts(rig);
  Target(rig, m, colour, parts);
  const float a = Progress(m);
  if (a >= 1) return;
  for (int c = 0; c < 4; ++c) {
    const float from = Component(m.colour_from[c]);
    colour[c] = from + (colour[c] - from) * a;
  }
  for (std::uint32_t p = 0; p < P; ++p) {
    const float from = Component(m.part_from[p]);
    parts[p] = from + (parts[p] - from) * a;
  }
}

void StartFade(const Rig& rig, MachineInstance& m, double mix, bool first_change_of_step) {
  if (first_change_of_step) {
    float colour[4], parts[format::kMaxParts];  // apart from m: the fade reads m.colour_from
    ShownColour(rig, m, colour, parts);
    const std::uint32_t P = BodyParts(rig);
    for (int c = 0; c < 4; ++c) m.colour_from[c] = colour[c];
    for (std::uint32_t p = 0; p < P; ++p) m.part_from[p] = parts[p];
    m.fade_elapsed = 0, m.fade_duration = 0;
  }
  if (mix > m.fade_duration) m.fade_duration = mix;
}

void SettleFade(const Rig& rig, MachineInstance& m) {
  float parts[format::kMaxParts];
  Target(rig, m, m.colour_from, parts);
  const std::uint32_t P = BodyParts(rig);
  for (std::uint32_t p = 0; p < format::kMaxParts; ++p) m.part_from[p] = p < P ? parts[p] : 1.0f;
  m.fade_elapsed = 0, m.fade_duration = 0;
}

}  // namespace detail

bool MachineColourJob::Validate() const {
  if (!rig || !rig->loaded() || rig->machine_layers().size == 0 || count > kMaxAnimatorBatch) return false;
  if (!machines.data || machines.size < count) return false;
  if (!colours.empty() && (!colours.data || colours.size < count)) return false;
  if (!part_opacities.empty() &&
      (rig->part_count() < 2 || !part_opacities.data || part_opacities.size / rig->part_count() < count))
    return false;
  return true;
}

bool MachineColourJob::Run() const {
  if (!Validate()) return false;
  // dt as the animator takes it: NaN or negative 0, beyond the bound the bound.
  const double step = dt > 0 ? (dt < kMaxAnimatorStep ? dt : kMaxAnimatorStep) : 0.0;
  const std::uint32_t P = detail::BodyParts(*rig);
  for (std::size_t i = 0; i < count; ++i) {
    MachineInstance& m = machines[i];
    if (std::isfinite(m.fade_elapsed) && m.fade_elapsed < m.fade_duration) m.fade_elapsed += step;
    float colour[4], parts[format::kMaxParts];
    detail::ShownColour(*rig, m, colour, parts);
    if (!colours.empty()) colours[i] = Colour{colour[0], colour[1], colour[2], colour[3]};
    if (!part_opacities.empty())
      for (std::uint32_t p = 0; p < P; ++p) part_opacities[i * P + p] = parts[p];
  }
  return true;
}

}  // namespace posemorph
