// meshctl's command line: the command, its arguments and flags, and the help text of each.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "client/connection.h"
#include "client/gis_import.h"
#include "client/size_grid.h"

namespace meshd::cli {

struct CliOptions {
  std::string command;  // generate, submit, watch, cancel, status, list, health, help
  std::vector<std::string> args;
  ConnectionOptions connection;
  bool json = false;
  bool help = false;

  // generate / submit / watch
  std::vector<std::string> outputs;  // -o FILE
  std::string format;                // --format NAME for every output
  std::string frames_dir;            // --frames DIR
  std::optional<std::string> backend;
  std::optional<int> priority;
  std::optional<int> snapshot_every;
  std::optional<double> timeout_s;
  std::string label;
  // A request without a file: --circle R | --rectangle W,H, optionally --hole R, and --h0.
  std::optional<double> circle, hole, h0;
  std::optional<double> sphere;  // --sphere R: a volume request, a ball (minus --hole R)
  std::optional<std::pair<double, double>> rectangle;
  std::optional<uint64_t> seed;
  // An imported outline (--import FILE and its flags); gis.simplify_tolerance stays 0 here:
  // build_request sets it to simplify * h0.
  GisImportOptions gis;
  std::optional<double> simplify;   // --simplify F: tolerance F * h0
  std::string import_name;          // --import-name; empty: the layer's name
  bool subtract_from_clip = false;  // --subtract-from-clip: the geometry is the clip box minus it
  // A signed-distance grid (--sdf-grid FILE.npy) placed by its origin and spacing.
  std::string sdf_grid;
  std::optional<Vec2> sdf_grid_origin, sdf_grid_spacing;
  // A gridded size term (--size-grid FILE, --size-grid-origin, --size-grid-spacing) and the
  // size field's gradation (--gradation G).
  SizeGridOptions size_grid;
  std::optional<double> gradation;
  // --grade H_MIN,SLOPE,H_MAX: a size term h = min(H_MAX, H_MIN + SLOPE |d|) about the import
  // (relative sizes; SLOPE per unit of the output CRS).
  std::optional<std::array<double, 3>> grade;
  // --feature ELEMENTS,H_MIN,H_MAX: a feature-size term, about ELEMENTS edges across the
  // domain's narrow parts, clamped to [H_MIN, H_MAX] (relative sizes; checked by the server).
  std::optional<std::array<double, 3>> feature;
  // list
  std::string state;
};

// Parses argv (without the program name). Throws Error(kInvalidArgument) naming the flag.
CliOptions parse_cli(const std::vector<std::string>& args);

// The help of `command`, or the overview for an empty or unknown one.
std::string help_text(const std::string& command);

}  // namespace meshd::cli
