// SPDX-License-Identifier: MIT
// The baked rig's binary layout, shared by the loader and by the bake's
// writer: tags, flags and limits here, the fixed-size records (header,
// section table entry, META, table entries, section headers) in
// posemorph/format/records.h. The authoritative description is
// runtime/FORMAT.md.
#pragma once
#include <cstddef>
#include <cstdint>

#include "posemorph/export.h"
#include "posemorph/format/records.h"

namespace posemorph::format {

constexpr unsigned char kMagic[8] = {'P', 'M', 'R', 'I', 'G', '\r', '\n', 0x1a};
constexpr std::uint16_t kVersionMajor = 1;
// 1.1 added the optional CANV section; 1.2 the weight grid's cell centres
// (META flag kMetaFlagGridCentres); 1.3 the compact encoding (META flag
// kMetaFlagCompact); 1.4 the texture-filter hint; 1.5 the drawing folder
// (kMetaFlagDrawingFolder); 1.6 parts drawn in order (kMetaFlagParts, PART),
// optionally an order per pose (kMetaFlagPartPoseOrders, PORD); 1.7 control
// channels (CHAN: attachments, each a nested rig driven by its own channel);
// 1.8 named events on paths (kMetaFlagEvents, EVNT); 1.9 a state machine
// (MACH, in the top-level rig only); 1.10 colours set by states (MACH's
// colour entries); 1.11 where the character stands and which way it faces
// (PLCE, optional); 1.12 a texture atlas (ATLS, optional); 1.13 compact
// positions of the poses after the first coded against pose 0's (QPOS's
// prediction field); 1.14 compact positions predicted from each vertex's
// earlier neighbours in the mesh. Older files load unchanged.
constexpr std::uint16_t kVersionMinor = 14;
constexpr std::uint32_t kHeaderSize = FileHeader::kSize;
constexpr std::uint32_t kSectionEntrySize = SectionEntry::kSize;
constexpr std::uint32_t kSectionAlignment = 16;
constexpr std::uint32_t kMaxSections = 64;

// Header field offsets (FileHeader), for tools that patch a file in place.
constexpr std::uint32_t kOffVersionMajor = offsetof(FileHeader, version_major);
constexpr std::uint32_t kOffVersionMinor = offsetof(FileHeader, version_minor);
constexpr std::uint32_t kOffHeaderSize = offsetof(FileHeader, header_size);
constexpr std::uint32_t kOffFileSize = offsetof(FileHeader, file_size);
constexpr std::uint32_t kOffSectionCount = offsetof(FileHeader, section_count);
constexpr std::uint32_t kOffFlags = offsetof(FileHeader, flags);
constexpr std::uint32_t kOffChecksum = offsetof(FileHeader, checksum);

constexpr std::uint32_t Tag(char a, char b, char c, char d) {
  return std::uint32_t(std::uint8_t(a)) | std::uint32_t(std::uint8_t(b)) << 8 | std::uint32_t(std::uint8_t(c)) << 16 |
         std::uint32_t(std::uint8_t(d)) << 24;
}

// Section tags.
constexpr std::uint32_t kMeta = Tag('M', 'E', 'T', 'A');
constexpr std::uint32_t kTriangles = Tag('T', 'R', 'I', 'S');
constexpr std::uint32_t kPosePositions = Tag('P', 'O', 'S', 'E');
constexpr std::uint32_t kPosePoints = Tag('P', 'P', 'N', 'T');
constexpr std::uint32_t kPoseCentroids = Tag('P', 'C', 'E', 'N');
constexpr std::uint32_t kVertexMasses = Tag('M', 'A', 'S', 'S');
constexpr std::uint32_t kGradients = Tag('G', 'R', 'A', 'D');
constexpr std::uint32_t kAngles = Tag('A', 'N', 'G', 'L');
constexpr std::uint32_t kStretches = Tag('S', 'H', 'E', 'R');  // the stretch matrices S (the tag keeps its old name)
constexpr std::uint32_t kPermutation = Tag('P', 'E', 'R', 'M');
constexpr std::uint32_t kFactorColumns = Tag('L', 'C', 'O', 'L');
constexpr std::uint32_t kFactorRows = Tag('L', 'R', 'O', 'W');
constexpr std::uint32_t kFactorValues = Tag('L', 'V', 'A', 'L');
constexpr std::uint32_t kFactorInvDiagonal = Tag('D', 'I', 'N', 'V');
constexpr std::uint32_t kWeightGrid = Tag('W', 'G', 'R', 'D');
constexpr std::uint32_t kStrings = Tag('S', 'T', 'R', 'S');
constexpr std::uint32_t kPaths = Tag('P', 'A', 'T', 'H');
constexpr std::uint32_t kPathKeys = Tag('P', 'K', 'E', 'Y');
constexpr std::uint32_t kUVs = Tag('U', 'V', 'S', ' ');
// Optional (format 1.1): per pose the drawing's canvas width and height and
// the rig origin's place on it (x, y down), in drawing units; zeros when the
// pose has no drawing. N x 4 doubles.
constexpr std::uint32_t kCanvases = Tag('C', 'A', 'N', 'V');

// META section: one Meta record (records.h).
constexpr std::uint32_t kMetaSize = Meta::kSize;
constexpr std::uint32_t kMetaFlagHasUVs = 1u;
// WGRD holds (cells_x+1)(cells_y+1) corner rows, then cells_x * cells_y
// centre rows (row-major in y then x), N weights each; each cell is split
// into four triangles at its centre. Without it (files before 1.2): corner
// rows only, each cell split on its (0,0)-(1,1) diagonal.
constexpr std::uint32_t kMetaFlagGridCentres = 2u;
// Compact encoding (1.3): positions, triangles, the permutation and the
// weight grid are stored quantised and bit-packed (QPOS, QTRI, QPRM, QGRD),
// uvs as affine maps of a pose's positions (QUVA) or as UVS, rotation angles
// as whole turns (QTRN) added to the principal angle; masses, centroids,
// gradients, angles, stretches and the factor are computed at load from the
// decoded positions, into the same arena layout. See runtime/FORMAT.md.
constexpr std::uint32_t kMetaFlagCompact = 4u;
// 1.4: the drawings are pixel art: renderers should sample them nearest (a
// hint; it changes no number the runtime computes).
constexpr std::uint32_t kMetaFlagNearestFilter = 8u;
// 1.5: STRS ends with one more string, the folder the image references
// resolve against (the description's folder at bake), relative to the rig
// file's folder, '/'-separated; for tools on the machine that baked
// (Rig::drawing_folder).
constexpr std::uint32_t kMetaFlagDrawingFolder = 16u;
// 1.6: the rig is drawn as parts (PART): STRS ends (after the drawing
// folder, when there is one) with each part's name, then each part's image
// reference for each pose (part by part, N each).
constexpr std::uint32_t kMetaFlagParts = 32u;
// PART section (1.6): a PartEntry per part (records.h). The parts cover the
// triangles in order: part 0 starts at triangle 0, each starts where the one
// before ends, the last ends at T; none is empty.
constexpr std::uint32_t kParts = Tag('P', 'A', 'R', 'T');
constexpr std::uint32_t kPartEntrySize = PartEntry::kSize;
constexpr std::uint32_t kMaxParts = 64;
// 1.6, with kMetaFlagParts: the draw order changes with the pose (PORD):
// per pose, per part an i32 draw order (N x M, pose-major). A frame draws in
// the order of its dominant drawing's pose (the largest texture weight);
// PART's order is pose 0's.
constexpr std::uint32_t kMetaFlagPartPoseOrders = 64u;
constexpr std::uint32_t kPartPoseOrders = Tag('P', 'O', 'R', 'D');
// CHAN section (1.7): a character with several control channels. The rig
// itself is channel 0; each attachment is a complete rig file (the nested
// rig, its own header, sections and checksum; never with a CHAN of its own)
// driven by another channel and pinned to a triangle of this rig:
//   a ChannelsHeader (records.h: C in 2..kMaxChannels, A in 1..kMaxAttachments);
//   A AttachmentEntry records;
//   then C names, each u32 length (1..kMaxChannelName) + bytes;
//   then the nested rigs, in attachment order, apart and inside the section.
constexpr std::uint32_t kChannels = Tag('C', 'H', 'A', 'N');
constexpr std::uint32_t kChannelsHeaderSize = ChannelsHeader::kSize;
constexpr std::uint32_t kAttachmentEntrySize = AttachmentEntry::kSize;
constexpr std::uint32_t kMaxChannels = 8;
constexpr std::uint32_t kMaxAttachments = 32;
constexpr std::uint32_t kMaxChannelName = 64;
// 1.8: paths carry named events (EVNT): STRS ends (after the part strings,
// when there are parts) with each event's name, in EVNT's order.
constexpr std::uint32_t kMetaFlagEvents = 128u;
// EVNT section (1.8): an EventEntry per event (records.h), sorted by path,
// then by time (ties keep their order); each time lies within its path's
// first and last key times. 1..kMaxEvents entries.
constexpr std::uint32_t kEvents = Tag('E', 'V', 'N', 'T');
constexpr std::uint32_t kEventEntrySize = EventEntry::kSize;
constexpr std::uint32_t kMaxEvents = 1u << 16;
// MACH section (1.9): a state machine of inputs, layers (one per channel
// at most), states and transitions with conditions (records.h,
// MachineHeader). Names: after the entries, each input's then each state's
// name, u32 length (1..kMaxMachineName) + bytes; the section ends there.
constexpr std::uint32_t kMachine = Tag('M', 'A', 'C', 'H');
// PLCE section (1.11, optional, the top-level rig only): where the character
// stands and which way it faces, one PlacementRecord (records.h). Without
// it the anchor is the bottom centre of pose 0's bounds, facing right.
constexpr std::uint32_t kPlacement = Tag('P', 'L', 'C', 'E');
constexpr std::uint32_t kPlacementFacingLeft = 1u;
constexpr double kMaxAnchor = 1e9;  // |anchor| in rig units
// ATLS section (1.12, optional; in the character's rig and in each
// attachment's): the drawings packed into texture pages (PNG files beside
// the rig file), AtlasHeader then its entries (records.h), then each page's
// name, u32 length (1..kMaxAtlasPageName) + bytes, a reference relative to
// the rig file's folder (image_reference.h); the section ends there. Every
// page of a rig has one size; a rig with an atlas has a canvas per pose
// (CANV). A region lies inside its page; its crop's corner within
// +-kMaxAtlasCanvasOffset of the canvas's.
constexpr std::uint32_t kAtlas = Tag('A', 'T', 'L', 'S');
constexpr std::uint32_t kAtlasPremultiplied = 1u;  // the pages hold premultiplied RGBA
constexpr std::uint32_t kMaxAtlasPages = 64;
constexpr std::uint32_t kMaxAtlasPageSize = 16384;
constexpr std::uint32_t kMaxAtlasPageName = 255;
constexpr std::int32_t kMaxAtlasCanvasOffset = 1 << 20;
constexpr std::uint32_t kMaxMachineInputs = 64;
constexpr std::uint32_t kMaxMachineStates = 1024;
constexpr std::uint32_t kMaxMachineTransitions = 4096;
constexpr std::uint32_t kMaxMachineConditions = 16384;
constexpr std::uint32_t kMaxMachineName = 64;
constexpr std::uint32_t kMachineStateLoopGiven = 1u, kMachineStateLoop = 2u;
constexpr std::uint32_t kMachineTransitionExitTime = 1u;
// A joint's barycentric weights are at most this far outside [0, 1].
constexpr double kMaxJointWeightOutside = 1e-3;

constexpr std::uint32_t kQuantPositions = Tag('Q', 'P', 'O', 'S');
constexpr std::uint32_t kQuantTriangles = Tag('Q', 'T', 'R', 'I');
constexpr std::uint32_t kQuantPermutation = Tag('Q', 'P', 'R', 'M');
constexpr std::uint32_t kQuantTurns = Tag('Q', 'T', 'R', 'N');
constexpr std::uint32_t kQuantGrid = Tag('Q', 'G', 'R', 'D');
constexpr std::uint32_t kAffineUVs = Tag('Q', 'U', 'V', 'A');
// Optional, not read by the loader: f64 error budget (drawing pixels), the
// largest vertex error the bake measured, the error at the pose points, and
// drawing pixels per rig unit. For `posemorph-bake info`.
constexpr std::uint32_t kCompactInfo = Tag('Q', 'I', 'N', 'F');

// PATH section: a PathEntry per path (records.h).
constexpr std::uint32_t kPathEntrySize = PathEntry::kSize;
constexpr std::uint32_t kPathFlagLoop = 1u;
constexpr std::uint32_t kPathInterpolationShift = 8;

// Limits the loader enforces so that hostile counts cannot make it allocate
// absurd amounts or overflow size arithmetic.
constexpr std::uint32_t kMaxVertices = 1u << 22;
constexpr std::uint32_t kMaxTriangles = 1u << 23;
constexpr std::uint32_t kMaxPoses = 64;
constexpr std::uint32_t kMaxGridCells = 2048;  // per axis
constexpr std::uint32_t kMaxPaths = 1024;
constexpr std::uint32_t kMaxPathKeys = 1u << 20;  // all paths together
constexpr std::uint32_t kMaxFactorNonzeros = 1u << 28;
constexpr std::uint32_t kMaxStringBytes = 1u << 20;
// A compact rig's factor is computed at load: its declared nonzeros may be
// at most this many per byte of the file, and the factorisation's work (the
// sum of its squared column counts) at most kMaxCompactFactorWork, so that
// time and memory stay bounded by the file's size.
constexpr std::uint32_t kMaxCompactNonzerosPerByte = 32;
constexpr std::uint64_t kMaxCompactFactorWork = std::uint64_t(1) << 31;
// A compact rig's arena may be at most this many times its file (plus 1 MiB).
constexpr std::uint32_t kMaxCompactExpansion = 256;
// Exp-Golomb codes in QGRD: at most this many leading zeros (values < 2^40).
constexpr std::uint32_t kMaxGolombZeros = 40;
// Magnitude limits on stored numbers, so that every evaluation of a rig that
// loads stays finite (with the weight limit of the jobs, jobs.h).
constexpr double kMaxAngle = 1e4;       // radians (about 1,600 turns)
constexpr double kMaxStretch = 1e4;     // entries of the symmetric stretch S
constexpr double kMaxGridWeight = 1e4;  // baked pose-space weights
constexpr double kMaxPathValue = 1e12;  // path key times and coordinates
constexpr double kMaxMagnitude = 1e15;  // everything else (positions, gradients, factor, ...)

PM_API std::uint32_t Crc32(const unsigned char* data, std::uint64_t size, std::uint32_t crc = 0);

}  // namespace posemorph::format
