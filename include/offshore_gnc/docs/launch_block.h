#pragma once
// The launch files' component blocks, written from the vehicles' manifests (closed_loop/manifest.h): each launch
// file a manifest names holds one block between a BEGIN and an END comment line with the args of the files and
// seeds it loads and a <node> per component; the rest of the file (its interface: the other args, includes,
// comments) is written by hand. `param_docs --launch launch/FILE.launch` prints the file with its block written
// anew; a test fails when a committed file differs.
#include <string>
#include <vector>

#include "offshore_gnc/closed_loop/manifest.h"

namespace offshore_gnc {
namespace docs {

// The launch files (names under launch/) the manifests' components and vehicle configs are started from, sorted.
std::vector<std::string> launchFiles(const std::vector<closed_loop::VehicleManifest>& manifests);

// The block of `launch` (a name under launch/), BEGIN and END lines included. A launch file named by several
// manifests (safety.launch) must come out the same from each; ConfigError otherwise, or for an arg declared twice
// with different defaults, or when no manifest names the file.
std::string launchBlock(const std::vector<closed_loop::VehicleManifest>& manifests, const std::string& launch);

// `text` (the launch file `launch`) with its block replaced by launchBlock(); ConfigError when the file has no
// BEGIN/END lines.
std::string withLaunchBlock(const std::string& text, const std::vector<closed_loop::VehicleManifest>& manifests,
                            const std::string& launch);

}  // namespace docs
}  // namespace offshore_gnc
