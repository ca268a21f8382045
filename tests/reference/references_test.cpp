// The reference tier: every row of references/references.tsv, regenerated from its stated system,
// parameters, sampling, N and seed, must land in its band. A failure names the source.

#include <gtest/gtest.h>

#include "chaos/models/validation.hpp"

namespace chaos {
// Names the row in test listings instead of dumping its bytes.
void PrintTo(const Reference& r, std::ostream* out) { *out << r.id << " (" << r.source << ")"; }
}  // namespace chaos

namespace {

class ReferenceCase : public ::testing::TestWithParam<chaos::Reference> {};

TEST_P(ReferenceCase, WithinBand) {
  const chaos::Reference& r = GetParam();
  const chaos::ValidationResult v = chaos::validate(r);
  EXPECT_TRUE(v.passed) << r.id << ": measured " << (v.measured ? std::to_string(*v.measured) : "none") << " outside ["
                        << r.low << ", " << r.high << "]; reference " << (r.value ? std::to_string(*r.value) : "-")
                        << " from " << r.source << " (" << r.kind << "): " << v.detail << "\n  note: " << r.note;
}

std::string case_name(const ::testing::TestParamInfo<chaos::Reference>& info) {
  std::string name = info.param.id;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(References, ReferenceCase, ::testing::ValuesIn(chaos::reference_table()), case_name);

}  // namespace
