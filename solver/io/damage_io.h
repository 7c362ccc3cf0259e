// The damage state of a tet mesh as a text file beside its TetGen files (`stem.damage`).
//
//   # galsculpt damage 2
//   <number of damaged edges>
//   <vertex> <vertex> [<at>]  one line per damaged edge, 0-based, the .node file's numbering;
//                             `at`, where a knife crossed the edge, is a fraction in [0, 1] from
//                             the first vertex of the line to the second (no `at`: no blade
//                             crossed it, e.g. fracture)
//
// Version 1 files (no `at` on any line) read as they are. Comments (#) and blank lines are
// ignored; the reader is strict (every edge must be an edge of the mesh, no repeats, `at`
// finite and in [0, 1]) and errors say `file:line: message`. Writes are atomic.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/io/atomic_file.h"
#include "solver/mesh/tet_mesh.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

// Per edge of a mesh: damaged or not, and where a blade crossed it (SimState's fields).
struct EdgeDamageState {
  std::vector<std::uint8_t> damaged;  // (nEdges) 1 = damaged
  std::vector<float> crossing;        // (nEdges) fraction along the edge, or kNoCrossing
  std::string setStamp;               // the file set it was written with, or empty
};

// `edges` sorted and unique (SimModel::edges, uniqueEdges); `damaged` one flag per edge;
// `crossing` one entry per edge (kNoCrossing where none) or empty for none at all.
void writeDamage(const std::filesystem::path& path, const std::vector<Edge>& edges,
                 const std::vector<std::uint8_t>& damaged, const std::vector<float>& crossing = {});

// The same as a member of a file set (written with the set's stamp, committed by the caller).
void addDamage(FileSet& set, const std::filesystem::path& path, const std::vector<Edge>& edges,
               const std::vector<std::uint8_t>& damaged, const std::vector<float>& crossing);

// One flag and one crossing per entry of `edges` (sorted and unique).
EdgeDamageState readDamage(const std::filesystem::path& path, const std::vector<Edge>& edges);

// Per tet: the fraction of its six edges that are damaged (for VTK cell data).
std::vector<double> tetDamageFraction(const std::vector<std::array<int, 6>>& tetEdges,
                                      const std::vector<std::uint8_t>& damaged);

}  // namespace galsculpt
