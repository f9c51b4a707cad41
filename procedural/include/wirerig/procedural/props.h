// Procedural props for the paper's physics examples (section 6, Figs. 5-8 and 10), each a mesh
// and the rig description that goes with it, like MakeOctopus (octopus.h). Every
// piece is a closed, outward-facing tube (MakeCylinder or MakeSweptTube) kept as its own mesh
// part, and each rig part is restricted to its own mesh parts. Metres, +Y up.
//
//   candles   (Fig. 5)  a row of upright candles along +X, "candle_0" ... "candle_<n-1>"; the
//                       first is the root part, the others its children (candle_0 is meant to
//                       stay unloaded, as the reference, so the others never move with it).
//   beam      (Fig. 6)  a round beam lying along +X, centred on the origin, with flat ends:
//                       one part "beam" whose spine runs along +X.
//   trunk     (Fig. 7)  a straight, tapered tree trunk standing on +Y with a flared root and a
//                       rounded top: one part "trunk".
//   lamp_post (Fig. 8)  a post on +Y (plinth, tapered neck, pole) with a globe lantern on
//                       top: parts "post" (root) and "lantern" (child).
//   chair     (Fig. 10) a cushion-like seat slab, a back slab at its rear (-Z) and four round
//                       legs: parts "seat" (root), "back", "leg_0" ... "leg_3" (children).
//                       The seat's spine runs along +X, the back's up +Y, each leg's down -Y
//                       from under the seat; leg i sits at (sx, sz) = (+,+), (-,+), (-,-), (+,-).
#pragma once

#include <string>

#include "wirerig/procedural/octopus.h"

namespace wirerig {

struct CandleRowParameters {
  int count = 6;             // candles, in [1, 16]
  double radius = 0.04;      // m
  double height = 0.5;       // m
  double spacing = 0.15;     // m between candle axes (> 2 radius)
  int radial_segments = 24;  // vertices around every ring
  int height_segments = 50;  // rings along each candle
  int profile_count = 25;    // profiles per candle (spine samples: 4 x profile_count)
  int points_per_profile = 16;
};

struct BeamParameters {
  double length = 2.0;   // m, along X
  double radius = 0.08;  // m
  int radial_segments = 24;
  int rings = 64;
  int profile_count = 16;
  int points_per_profile = 16;
};

struct TrunkParameters {
  double height = 2.5;        // m
  double base_radius = 0.16;  // m, above the root flare
  double top_radius = 0.08;   // m, below the rounded top (< base_radius)
  double flare = 0.5;         // extra radius at the ground, as a fraction of base_radius, [0, 2]
  int radial_segments = 24;
  int rings = 48;
  int profile_count = 16;
  int points_per_profile = 24;
};

struct LampPostParameters {
  double height = 3.0;           // m, ground to the top of the post (the lantern sits above)
  double pole_radius = 0.06;     // m
  double base_radius = 0.15;     // m, the plinth (> pole_radius)
  double base_height = 0.4;      // m, the plinth and its taper (< height / 2)
  double lantern_radius = 0.18;  // m
  double lantern_height = 0.45;  // m
  int radial_segments = 24;
  int rings = 64;          // rings along the post (the lantern gets a third)
  int profile_count = 20;  // profiles on the post (the lantern gets 6)
  int points_per_profile = 24;
};

struct ChairParameters {
  double seat_width = 0.46;      // m, along X
  double seat_depth = 0.44;      // m, along Z
  double seat_height = 0.46;     // m, floor to the top of the seat
  double seat_thickness = 0.07;  // m
  double leg_radius = 0.022;     // m
  double back_height = 0.5;      // m, above the seat
  double back_thickness = 0.05;  // m
  int radial_segments = 24;
  int rings = 32;          // rings along every piece
  int profile_count = 12;  // profiles per part
  int points_per_profile = 24;
};

// Each: empty when valid, else "<field>: <reason>".
std::string ValidateCandleRowParameters(const CandleRowParameters& parameters);
std::string ValidateBeamParameters(const BeamParameters& parameters);
std::string ValidateTrunkParameters(const TrunkParameters& parameters);
std::string ValidateLampPostParameters(const LampPostParameters& parameters);
std::string ValidateChairParameters(const ChairParameters& parameters);

// Each validates its parameters first; the error names the field.
Result<ProceduralRigSource> MakeCandleRow(const CandleRowParameters& parameters = {});
Result<ProceduralRigSource> MakeBeam(const BeamParameters& parameters = {});
Result<ProceduralRigSource> MakeTrunk(const TrunkParameters& parameters = {});
Result<ProceduralRigSource> MakeLampPost(const LampPostParameters& parameters = {});
Result<ProceduralRigSource> MakeChair(const ChairParameters& parameters = {});

}  // namespace wirerig
