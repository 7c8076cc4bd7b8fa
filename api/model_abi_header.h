// The text of runtime/abi/mbfe_model_abi.h, as this build was configured
// with (api/model_abi_header.cpp.in).
#pragma once

namespace mbfe::internal {

/// The whole header, written beside every solver compiled at run time.
extern const char* const kModelAbiHeader;

}  // namespace mbfe::internal
