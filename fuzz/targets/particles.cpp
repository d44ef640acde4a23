// SPDX-License-Identifier: BSD-3-Clause
// Particles (geometry/particle_loader.h): an input with an ATOM or HETATM line is read as PDB,
// anything else as the text list `x y z r [material]`. Loaded spheres must be finite, have a
// positive radius and a material that exists; a broken set aborts (a finding).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "fuzz/fuzz_input.h"
#include "fuzz/fuzz_targets.h"
#include "geometry/particle_loader.h"

namespace voxlink::fuzz {
namespace {

bool looksLikePdb(Input input) {
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  return text.starts_with("ATOM") || text.starts_with("HETATM") ||
         text.find("\nATOM") != std::string_view::npos ||
         text.find("\nHETATM") != std::string_view::npos;
}

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "loaded particles are inconsistent: %s\n", what);
  std::abort();
}

}  // namespace

Status fuzzParticles(Input input) {
  const std::string path =
      scratch().write(splitFuzzFiles(input, looksLikePdb(input) ? "input.pdb" : "input.txt"));
  auto set = geometry::loadParticles(path);
  if (!set) return set.status();
  if (set->spheres.empty()) broken("no spheres");
  for (const geometry::Sphere& s : set->spheres) {
    for (float c : s.center)
      if (!std::isfinite(c)) broken("non-finite centre");
    if (!(s.radius > 0.0f) || !std::isfinite(s.radius)) broken("radius not positive and finite");
    if (s.material >= set->materials.size()) broken("material index out of range");
  }
  return Status::ok();
}

}  // namespace voxlink::fuzz
