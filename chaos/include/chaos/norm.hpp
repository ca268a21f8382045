#pragma once
// The distance used between embedded points. The maximum norm is the default everywhere, as in
// the seed paper (Eq. 32) and TISEAN; the Euclidean norm is available on request.

namespace chaos {

enum class Norm { max, euclidean };

const char* to_string(Norm norm) noexcept;

}  // namespace chaos
