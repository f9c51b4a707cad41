#include "wirerig/viewer/input_script.h"

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(InputScript, ParsesEveryEvent) {
  const char* text =
      "# a comment\n"
      "0 move 0.5 0.25\n"
      "1 move-by -0.1 0.0   # trailing comment\n"
      "\n"
      "2 move-to-wire 3 0.9\n"
      "3 press left\n"
      "3 release right\n"
      "4 scroll -2\n"
      "5 key f\n"
      "5 key space\n";
  Result<std::vector<InputEvent>> events = ParseInputScript(text, "test.input");
  ASSERT_TRUE(events) << events.error();
  const auto& e = events.value();
  ASSERT_EQ(e.size(), 8u);
  EXPECT_EQ(e[0].type, InputEventType::kMove);
  EXPECT_FLOAT_EQ(e[0].y, 0.25f);
  EXPECT_EQ(e[1].type, InputEventType::kMoveBy);
  EXPECT_FLOAT_EQ(e[1].x, -0.1f);
  EXPECT_EQ(e[2].type, InputEventType::kMoveToWire);
  EXPECT_EQ(e[2].wire, 3u);
  EXPECT_FLOAT_EQ(e[2].x, 0.9f);
  EXPECT_EQ(e[3].type, InputEventType::kPress);
  EXPECT_EQ(e[3].button, MouseButton::kLeft);
  EXPECT_EQ(e[4].button, MouseButton::kRight);
  EXPECT_FLOAT_EQ(e[5].y, -2.0f);
  EXPECT_EQ(e[6].key, 'F');
  EXPECT_EQ(e[7].key, ' ');
  EXPECT_EQ(e[7].frame, 5);
}

TEST(InputScript, ParsesMoveToGizmo) {
  Result<std::vector<InputEvent>> events =
      ParseInputScript("6 move-to-gizmo y 0.25\n7 move-to-gizmo x 0\n", "test.input");
  ASSERT_TRUE(events) << events.error();
  const auto& e = events.value();
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].type, InputEventType::kMoveToGizmo);
  EXPECT_EQ(e[0].axis, 1);
  EXPECT_FLOAT_EQ(e[0].x, 0.25f);
  EXPECT_EQ(e[1].axis, 0);
  EXPECT_EQ(e[1].frame, 7);
}

TEST(InputScript, ErrorsNameTheSourceAndLine) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
      {"0 move 0.5\n", "s.input:1: move takes two numbers"},
      {"0 move 0.5 0.5\nx press left\n", "s.input:2: the line must start with a frame number"},
      {"3 key f\n2 key f\n", "s.input:2: frame 2 comes before"},
      {"0 press thumb\n", "s.input:1: press takes a button"},
      {"0 jump\n", "s.input:1: unknown event 'jump'"},
      {"0 move-to-wire 1 1.5\n", "s.input:1: move-to-wire takes"},
      {"0 move-to-gizmo w 0.5\n", "s.input:1: move-to-gizmo takes"},
      {"0 move-to-gizmo z 2\n", "s.input:1: move-to-gizmo takes"},
      {"0 key F1\n", "s.input:1: key takes"},
      {"-1 key f\n", "s.input:1: the line must start"},
      {"5\n", "s.input:1: an event name must follow"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    Result<std::vector<InputEvent>> events = ParseInputScript(c.text, "s.input");
    ASSERT_FALSE(events);
    EXPECT_NE(events.error().find(c.expected), std::string::npos) << events.error();
  }
}

TEST(InputScript, MissingFileIsNamed) {
  Result<std::vector<InputEvent>> events = LoadInputScript("/nonexistent/drag.input");
  ASSERT_FALSE(events);
  EXPECT_NE(events.error().find("/nonexistent/drag.input"), std::string::npos);
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
