#pragma once
// The study's per-point analysis against chaos::analyse_series on the same series: the delay, the
// Theiler window, the embedding dimension and D2, with the rules that chose them, must be equal
// (the study runs `chaos analyze`'s pipeline; tests/study/unit and tests/study/reference use it).

#include <gtest/gtest.h>

#include "chaos/automatic_analysis.hpp"
#include "study/series_analysis.hpp"

inline void expect_same_as_analyze(const study::SeriesAnalysis& a, const chaos::AutomaticAnalysis& reference) {
  ASSERT_TRUE(reference.d2) << reference.stopped;
  EXPECT_EQ(a.delay, reference.delay);
  EXPECT_EQ(a.delay_source, reference.delay_source);
  EXPECT_EQ(a.theiler, reference.theiler);
  EXPECT_EQ(a.theiler_source, reference.theiler_source);
  EXPECT_EQ(a.embedding_dimension, reference.dimension);
  EXPECT_EQ(a.d2_status, chaos::to_string(reference.d2->status));
  EXPECT_EQ(a.d2, reference.d2->d2);
}
