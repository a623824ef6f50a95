// The BodyKinematics display's Legend (doc/rviz.md) in a real rviz (VisualizationManager and
// RenderPanel under Xvfb, the plugin loaded by pluginlib as rviz loads it): a status row per
// color, shown at start and again after each of rviz's resets, which clear a display's
// statuses: Auto Frame's change of the Fixed Frame (rviz's fixedFrameChanged), the Reset button
// (resetTime), a display's reset(). Each row's text fits the value column of the shipped
// configs' Displays panel whole. Run by test/rviz/legend_reset_test.sh (an Xvfb screen and a
// ROS master of its own).
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rviz/display.h>
#include <rviz/properties/status_list.h>
#include <rviz/render_panel.h>
#include <rviz/visualization_manager.h>

#include <QApplication>
#include <QFontMetrics>
#include <map>
#include <string>

namespace {

// The legend of the default colors (mb_kinematics/viz/legend.h), as status rows.
const std::map<std::string, std::string> kLegend = {{"Legend: cyan", "velocity of G_k, m/s"},
                                                    {"Legend: orange", "accel. of G_k, m/s^2"},
                                                    {"Legend: magenta", "omega_k, rad/s"},
                                                    {"Legend: yellow", "alpha_k, rad/s^2"},
                                                    {"Legend: white", "spheres at G_k"}};

// The value column of the shipped configs' Displays panel (config/mb_kinematics.rviz at
// 1280x900: x 172 to 340 of the screenshot, less the item's margins), px.
constexpr int kValueColumn = 160;

// One rviz for every test (Ogre's resources are made once per process).
class LegendReset : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    panel_ = new rviz::RenderPanel;
    manager_ = new rviz::VisualizationManager(panel_);
    panel_->initialize(manager_->getSceneManager(), manager_);
    manager_->initialize();
    manager_->startUpdate();
    display_ = manager_->createDisplay("mb_kinematics/BodyKinematics", "BodyKinematics", true);
  }
  static void TearDownTestSuite() {
    delete manager_;
    delete panel_;
  }
  void SetUp() override {
    ASSERT_NE(display_, nullptr);
    ASSERT_EQ(display_->getClassId(), "mb_kinematics/BodyKinematics");
  }

  // The display's status rows whose name starts with "Legend", name -> text.
  static std::map<std::string, std::string> legend() {
    QApplication::processEvents();
    std::map<std::string, std::string> rows;
    for (int i = 0; i < display_->numChildren(); ++i) {
      const auto* list = dynamic_cast<rviz::StatusList*>(display_->childAt(i));
      if (!list) continue;
      for (int j = 0; j < list->numChildren(); ++j) {
        const std::string name = list->childAt(j)->getName().toStdString();
        if (name.rfind("Legend", 0) == 0)
          rows[name] = list->childAt(j)->getValue().toString().toStdString();
      }
    }
    return rows;
  }

  static rviz::RenderPanel* panel_;
  static rviz::VisualizationManager* manager_;
  static rviz::Display* display_;
};
rviz::RenderPanel* LegendReset::panel_ = nullptr;
rviz::VisualizationManager* LegendReset::manager_ = nullptr;
rviz::Display* LegendReset::display_ = nullptr;

TEST_F(LegendReset, ShownAtStart) { EXPECT_EQ(legend(), kLegend); }

// Auto Frame sets the Fixed Frame (adoptFrame); rviz then resets the display.
TEST_F(LegendReset, ShownAfterTheFixedFrameChanges) {
  manager_->setFixedFrame("base_link");
  EXPECT_EQ(legend(), kLegend);
  manager_->setFixedFrame("odom");
  EXPECT_EQ(legend(), kLegend);
}

TEST_F(LegendReset, ShownAfterTheResetButton) {
  manager_->resetTime();  // what rviz's Reset button calls
  EXPECT_EQ(legend(), kLegend);
  display_->reset();
  EXPECT_EQ(legend(), kLegend);
}

// Readable whole: no row's text is cut off in the Displays panel's value column.
TEST_F(LegendReset, EveryRowFitsTheDisplaysPanel) {
  const QFontMetrics metrics(QApplication::font());
  const std::map<std::string, std::string> rows = legend();
  ASSERT_EQ(rows.size(), kLegend.size());
  for (const auto& row : rows)
    EXPECT_LE(metrics.horizontalAdvance(QString::fromStdString(row.second)), kValueColumn)
        << row.first << ": " << row.second;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "legend_reset_test", ros::init_options::AnonymousName);
  QApplication app(argc, argv);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
