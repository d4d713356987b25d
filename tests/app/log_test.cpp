// SPDX-License-Identifier: MIT
#include "meshmorph/log.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace meshmorph {
namespace {

TEST(LogSink, DeliversUpToTheChosenLevelAndIsSilentWithoutSink) {
  std::vector<std::string> got;
  set_log_sink([&](LogLevel level, std::string_view m) { got.push_back(std::to_string(int(level)) + std::string(m)); },
               LogLevel::Progress);
  log_warning("w");
  log_info("i");
  log_progress("p");
  log_detail("d");  // above Progress: dropped
  EXPECT_TRUE(log_enabled(LogLevel::Progress));
  EXPECT_FALSE(log_enabled(LogLevel::Detail));
  EXPECT_EQ(got, (std::vector<std::string>{"1w", "2i", "3p"}));
  set_log_sink({});
  log_message(LogLevel::Error, "e");
  EXPECT_FALSE(log_enabled(LogLevel::Error));
  EXPECT_EQ(got.size(), 3u);
}

}  // namespace
}  // namespace meshmorph
