// The one source of test_precompiled_header (tests/CMakeLists.txt): the target exists to build
// gtest.h's precompiled header, which every test executable reuses.
