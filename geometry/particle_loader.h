// SPDX-License-Identifier: BSD-3-Clause
// Loads particles (implicit spheres) from PDB files or from a plain text / CSV list.
//
// PDB (.pdb, .ent; any case): ATOM and HETATM records, fixed columns (1-based): x 31-38,
// y 39-46, z 47-54 (Angstrom), element 77-78. Without an element the atom name (columns 13-16)
// gives it by the PDB convention: " CA " carbon, "CA  " calcium, "FE  " iron, "HG21" hydrogen.
// Every record counts (all MODELs, all alternate locations), as the PDB file lists them. The radius
// is the element's van der Waals radius (Bondi 1964, J. Phys. Chem. 68:441, Table I; see
// vanDerWaalsRadius); elements Bondi did not tabulate (Ca, Fe, ...) get kDefaultVdwRadius. The
// material index names the element (ParticleSet::materials holds "C", "N", ...).
//
// Text (any other extension): one sphere per line, `x y z r [material]`, separated by commas
// and/or white space; `#` starts a comment; blank lines are skipped; a first line whose first
// field is not a number is a header and is skipped. `material` is a name (any token); spheres
// without one get the material "default". The radius must be > 0.
//
// Errors, one line naming the file and line: unreadable file, a truncated ATOM/HETATM record, a
// field that is not a number, a non-finite coordinate or radius, a radius <= 0, no spheres,
// more than 65536 materials.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace voxlink::geometry {

struct Sphere {
  std::array<float, 3> center{};
  float radius = 0.0f;
  uint16_t material = 0;  // index into ParticleSet::materials
};

struct ParticleSet {
  std::vector<Sphere> spheres;
  std::vector<std::string> materials;  // element symbols (PDB) or material names (text)
};

// Radius used for elements without a Bondi radius, in Angstrom.
inline constexpr float kDefaultVdwRadius = 2.0f;

// Bondi's van der Waals radius of `element` (case-insensitive symbol) in Angstrom, or 0 when
// the table does not list it.
float vanDerWaalsRadius(std::string_view element);

// Picks the reader by extension (.pdb/.ent -> PDB, anything else -> text).
Result<ParticleSet> loadParticles(const std::string& path);
Result<ParticleSet> loadPdb(const std::string& path);
Result<ParticleSet> loadParticleText(const std::string& path);

}  // namespace voxlink::geometry
