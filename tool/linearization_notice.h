// What `mbfe stability` and `mbfe modal` say before linearising a large
// coupled model: the dense eigenproblem of its 2 n states grows as n^3 and
// can take many minutes, which a user should know before waiting.
#pragma once

#include <string>

namespace mbfe::tool {

/// Coupled models with more coordinates than this get the notice.
inline constexpr int kLinearizationNoticeCoordinates = 1000;

/// The notice for a coupled model of `coordinates` coordinates linearised
/// `variants` times (original, and adjusted when it has an adjustment), with
/// an estimate from a measured run; "" for a model that linearises quickly.
std::string linearization_notice(const std::string& command, int coordinates, int variants);

}  // namespace mbfe::tool
