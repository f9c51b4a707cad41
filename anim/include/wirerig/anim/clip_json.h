// JSON form of clips, as scene files hold them (docs/scene-format.md).
//   track:  a constant (a number, or [x, y, z] for vectors), or
//           {"interpolation": "linear" (default for every key), "keys": [KEY, ...]} with KEY
//           either {"time": s, "value": v, "interpolation": name (optional)} or [time, value]
//           or [time, value, interpolation].
//   clip:   {"name", "duration", "loop", "parts": [...], "profiles": [...]}; see clip.h for
//           what each channel drives.
// Readers throw FieldError (rig/json_fields.h) with the JSON pointer of the field at fault;
// ClipToJson writes a form ReadClip reads back exactly.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "wirerig/anim/clip.h"
#include "wirerig/io/json_fields.h"

namespace wirerig {

RawClip ReadClip(const JsonObject& object);
nlohmann::json ClipToJson(const RawClip& clip);

}  // namespace wirerig
