// reference/peer/peer_scenes.hpp — the perspective scenes the peer comparison and the speed benchmark
// share: the Stanford bunny (glmark2-data) and a grazing textured plane. Built in double with
// GLM (0..1 clip depth, perspectiveRH_ZO), emitted as float32 clip-space triangles.
#pragma once

#include <string>
#include <vector>

#include "model/unit/io.hpp"

namespace fxr::peer {

inline constexpr const char* kBunnyPath = "/usr/share/glmark2/models/bunny.obj";

struct PeerScene {
  std::string name;
  std::string note;  // e.g. why a generated mesh replaced the bunny
  DrawState st;
  std::vector<ClipTriangle> tris;
};

// The bunny framed by a fixed camera at size × size (it fills about half of the image).
// Varyings (num_varyings ≤ 2): planar u, v ∈ [0, 16] from object x, y. When the OBJ file is
// missing or unreadable, a generated sphere of about the same triangle count is used instead
// and `note` says so.
PeerScene bunny_scene(int size, int num_varyings, const std::string& path = kBunnyPath);

// A plane seen at a grazing angle (y = 0, camera 1 unit above it, looking at the horizon),
// covering the lower part of the image: fill-bound. u, v ∈ [0, 16] across it (num_varyings ≤ 2).
// The plane stays in front of the near plane; its sides reach past the image edges.
PeerScene grazing_plane_scene(int size, int num_varyings);

}  // namespace fxr::peer
