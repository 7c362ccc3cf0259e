// The damage state of a tet mesh as a text file beside its TetGen files (`stem.damage`).
//
//   # galsculpt damage 1
//   <number of damaged edges>
//   <vertex> <vertex>        one line per damaged edge, 0-based, the .node file's numbering
//
// Comments (#) and blank lines are ignored; the reader is strict (every edge must be an edge of
// the mesh, no repeats) and errors say `file:line: message`. Writes are atomic.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "tet_mesh.h"

namespace galsculpt {

// `edges` sorted and unique (SimModel::edges, uniqueEdges); `damaged` one flag per edge.
void writeDamage(const std::filesystem::path& path, const std::vector<Edge>& edges,
                 const std::vector<std::uint8_t>& damaged);

// One flag per entry of `edges` (sorted and unique).
std::vector<std::uint8_t> readDamage(const std::filesystem::path& path,
                                     const std::vector<Edge>& edges);

// Per tet: the fraction of its six edges that are damaged (for VTK cell data).
std::vector<double> tetDamageFraction(const std::vector<std::array<int, 6>>& tetEdges,
                                      const std::vector<std::uint8_t>& damaged);

}  // namespace galsculpt
