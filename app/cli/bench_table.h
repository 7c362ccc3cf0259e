// The text `galsculpt bench` prints (app/cli/bench_command.cpp): the columns of its rows.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace galsculpt {

// The header line of the rows (no newline).
std::string benchHeader();
// One measurement's row (a setting's, or a --cracks count's), or its error.
std::string benchRow(const nlohmann::json& result);
// With several windows, each cut count's cost against the uncut frame in every window, and the
// median of those ratios.
void printWindowSummary(const std::vector<nlohmann::json>& rows, std::ostream& out);

}  // namespace galsculpt
