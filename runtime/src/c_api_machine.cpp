// SPDX-License-Identifier: MIT
// The C API for the state machine (posemorph/state_machine.h): machines in
// caller memory, inputs, steps into the animator's tracks.
#include <cstdint>

#include "c_api_internal.h"
#include "posemorph/animator.h"
#include "posemorph/posemorph.h"
#include "posemorph/state_machine.h"

using namespace posemorph::c_api;  // NOLINT(google-build-using-namespace): the C API's own helpers
using posemorph::MachineInstance;
using posemorph::Span;

static_assert(PM_ANIMATOR_ALIGNMENT >= alignof(MachineInstance) &&
                  PM_ANIMATOR_ALIGNMENT % alignof(MachineInstance) == 0,
              "published alignment");

namespace {

bool HasMachine(const pm_rig* rig) { return rig && rig->rig.machine_layers().size > 0; }

// Character `character`'s machine in caller memory, or null.
MachineInstance* At(const pm_rig* rig, const void* machines, size_t capacity, size_t character) {
  if (!HasMachine(rig) || !machines || !Aligned(static_cast<const MachineInstance*>(machines))) return nullptr;
  if (character >= capacity / sizeof(MachineInstance)) return nullptr;
  return const_cast<MachineInstance*>(static_cast<const MachineInstance*>(machines)) + character;
}

int Result(bool ok) { return ok ? PM_OK : PM_ERROR_INVALID_ARGUMENT; }

}  // namespace

extern "C" {

size_t pm_machine_size(const pm_rig* rig, size_t count) {
  return HasMachine(rig) && count <= posemorph::kMaxAnimatorBatch ? count * sizeof(MachineInstance) : 0;
}

int pm_machine_reset(const pm_rig* rig, void* machines, size_t capacity, size_t count) {
  if (!HasMachine(rig) || !machines || count > posemorph::kMaxAnimatorBatch) return PM_ERROR_INVALID_ARGUMENT;
  if (!Aligned(static_cast<MachineInstance*>(machines))) return PM_ERROR_INVALID_ARGUMENT;
  if (capacity / sizeof(MachineInstance) < count) return PM_ERROR_BUFFER_TOO_SMALL;
  for (size_t i = 0; i < count; ++i) posemorph::MachineReset(rig->rig, static_cast<MachineInstance*>(machines) + i);
  return PM_OK;
}

int pm_machine_find_input(const pm_rig* rig, const char* name) { return rig ? rig->rig.FindMachineInput(name) : -1; }
int pm_machine_find_state(const pm_rig* rig, const char* name) { return rig ? rig->rig.FindMachineState(name) : -1; }

int pm_machine_state_name(const pm_rig* rig, uint32_t state, char* out, size_t capacity, size_t* length) {
  const bool valid = rig && state < rig->rig.machine_states().size;
  return CopyString(valid ? rig->rig.machine_states()[state].name : posemorph::StringView{}, valid, out, capacity,
                    length);
}

int pm_machine_set_bool(const pm_rig* rig, void* machines, size_t capacity, size_t character, uint32_t input,
                        int value) {
  MachineInstance* m = At(rig, machines, capacity, character);
  return Result(m && posemorph::MachineSetBool(rig->rig, m, input, value != 0));
}

int pm_machine_set_number(const pm_rig* rig, void* machines, size_t capacity, size_t character, uint32_t input,
                          double value) {
  MachineInstance* m = At(rig, machines, capacity, character);
  return Result(m && posemorph::MachineSetNumber(rig->rig, m, input, value));
}

int pm_machine_set_point(const pm_rig* rig, void* machines, size_t capacity, size_t character, uint32_t input, double x,
                         double y) {
  MachineInstance* m = At(rig, machines, capacity, character);
  return Result(m && posemorph::MachineSetPoint(rig->rig, m, input, x, y));
}

int pm_machine_fire(const pm_rig* rig, void* machines, size_t capacity, size_t character, uint32_t input) {
  MachineInstance* m = At(rig, machines, capacity, character);
  return Result(m && posemorph::MachineFire(rig->rig, m, input));
}

int pm_machine_state(const pm_rig* rig, const void* machines, size_t capacity, size_t character, uint32_t layer) {
  const MachineInstance* m = At(rig, machines, capacity, character);
  if (!m || layer >= rig->rig.machine_layers().size || !m->started) return -1;
  return int(m->state[layer]);
}

int pm_machine_step(const pm_rig* rig, void* machines, size_t capacity, size_t count, void* tracks,
                    size_t tracks_capacity) {
  if (!HasMachine(rig) || !machines || !tracks || count > posemorph::kMaxAnimatorBatch)
    return PM_ERROR_INVALID_ARGUMENT;
  if (!Aligned(static_cast<MachineInstance*>(machines)) || !Aligned(static_cast<posemorph::AnimatorTrack*>(tracks)))
    return PM_ERROR_INVALID_ARGUMENT;
  const std::size_t C = rig->rig.channel_count();
  if (capacity / sizeof(MachineInstance) < count || tracks_capacity / sizeof(posemorph::AnimatorTrack) < count * C)
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::MachineStepJob job;
  job.rig = &rig->rig, job.count = count;
  job.machines = {static_cast<MachineInstance*>(machines), count};
  job.tracks = {static_cast<posemorph::AnimatorTrack*>(tracks), count * C};
  return Result(job.Run());
}

int pm_machine_colours(const pm_rig* rig, void* machines, size_t capacity, size_t count, double dt, pm_colour* colours,
                       float* part_opacities, size_t part_opacities_capacity) {
  if (!HasMachine(rig) || !machines || count > posemorph::kMaxAnimatorBatch) return PM_ERROR_INVALID_ARGUMENT;
  if (!Aligned(static_cast<MachineInstance*>(machines))) return PM_ERROR_INVALID_ARGUMENT;
  if (part_opacities && rig->rig.part_count() < 2) return PM_ERROR_INVALID_ARGUMENT;
  if (capacity / sizeof(MachineInstance) < count ||
      (part_opacities && part_opacities_capacity / rig->rig.part_count() < count))
    return PM_ERROR_BUFFER_TOO_SMALL;
  posemorph::MachineColourJob job;
  job.rig = &rig->rig, job.count = count, job.dt = dt;
  job.machines = {static_cast<MachineInstance*>(machines), count};
  if (colours) job.colours = {reinterpret_cast<posemorph::Colour*>(colours), count};
  if (part_opacities) job.part_opacities = {part_opacities, count * rig->rig.part_count()};
  return Result(job.Run());
}

}  // extern "C"
