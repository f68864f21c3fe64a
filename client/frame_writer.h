// --frames DIR: an SVG of every snapshot the server streams, so that a user can watch the mesh
// settle (of a volume, its surface). Keeps the triangles (tetrahedra) of the last snapshot that
// carried them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "meshd/v1/service.pb.h"

namespace meshd::cli {

class FrameWriter {
 public:
  // Creates `dir` if needed. Throws Error(kInvalidArgument) naming "--frames" when it cannot.
  explicit FrameWriter(std::string dir);
  // Writes DIR/frame_<iteration, 6 digits>.svg. Returns the path.
  std::string write(const v1::Snapshot& snapshot);
  int frames() const { return frames_; }

 private:
  void write_plane(const v1::Snapshot& snapshot, const std::string& path);
  void write_volume(const v1::Snapshot& snapshot, const std::string& path);

  std::string dir_;
  std::vector<std::array<int32_t, 3>> triangles_;
  std::vector<std::array<int32_t, 4>> tetrahedra_;
  int frames_ = 0;
};

}  // namespace meshd::cli
