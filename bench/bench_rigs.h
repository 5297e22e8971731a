// SPDX-License-Identifier: MIT
// Rigs the benchmarks share, baked once per process.
#pragma once
#include "posemorph/rig.h"

// Pell with a face channel (assets/pell/pell-face.json, exact), or null
// when its drawings were not built (parts_bench.cpp).
const posemorph::Rig* PellFaceRig();
