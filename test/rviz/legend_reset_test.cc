// The BodyKinematics display's Legend (doc/rviz.md) in a real rviz (VisualizationManager and
// RenderPanel under Xvfb, the plugin loaded by pluginlib as rviz loads it): a status row per
// color, shown at start and again after each of rviz's resets, which clear a display's
// statuses: Auto Frame's change of the Fixed Frame (rviz's fixedFrameChanged), the Reset button
// (resetTime), a display's reset(). Each row's name and text show whole in a property tree of
// the shipped configs' Displays panel's geometry. Run by test/rviz/legend_reset_test.sh (an Xvfb
// screen and a ROS master of its own).
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rviz/display.h>
#include <rviz/properties/property_tree_model.h>
#include <rviz/properties/property_tree_widget.h>
#include <rviz/properties/status_list.h>
#include <rviz/render_panel.h>
#include <rviz/visualization_manager.h>

#include <QApplication>
#include <QFontMetrics>
#include <QStyle>
#include <map>
#include <set>
#include <string>

namespace {

// The legend of the default colors (mb_kinematics/viz/legend.h), as status rows named by color.
const std::map<std::string, std::string> kLegend = {{"cyan", "velocity of G_k, m/s"},
                                                    {"orange", "accel. of G_k, m/s^2"},
                                                    {"magenta", "omega_k, rad/s"},
                                                    {"yellow", "alpha_k, rad/s^2"},
                                                    {"white", "spheres at G_k"}};
// The names mbk::color_name gives, and "Legend" (nothing shown).
const std::set<std::string> kLegendNames = {"red",     "orange", "yellow", "green", "cyan",  "blue",
                                            "magenta", "white",  "grey",   "black", "Legend"};

// The Displays panel of the shipped configs (config/mb_kinematics.rviz at 1280x900): 341 px wide,
// its name column 171 px (measured on rviz_robot_panda's screenshot).
constexpr int kPanelWidth = 341, kNameColumn = 171;

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

  // The display's legend rows, name -> text.
  static std::map<std::string, std::string> legend() {
    QApplication::processEvents();
    std::map<std::string, std::string> rows;
    for (int i = 0; i < display_->numChildren(); ++i) {
      const auto* list = dynamic_cast<rviz::StatusList*>(display_->childAt(i));
      if (!list) continue;
      for (int j = 0; j < list->numChildren(); ++j) {
        const std::string name = list->childAt(j)->getName().toStdString();
        if (kLegendNames.count(name))
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

// Readable whole: in a property tree of the Displays panel's width and name column, expanded as
// a user opens the display's status, no row's name or text is cut off (elided).
TEST_F(LegendReset, EveryRowShowsWholeInTheDisplaysPanel) {
  rviz::PropertyTreeWidget tree;
  tree.setModel(manager_->getDisplayTreeModel());
  tree.resize(kPanelWidth, 700);
  tree.setColumnWidth(0, kNameColumn);
  tree.expandAll();
  tree.show();
  QApplication::processEvents();
  const QFontMetrics metrics(tree.font());
  const int icon = tree.style()->pixelMetric(QStyle::PM_SmallIconSize) + 8;  // and its margins
  int rows = 0;
  for (int i = 0; i < display_->numChildren(); ++i) {
    rviz::Property* list = display_->childAt(i);
    if (!dynamic_cast<rviz::StatusList*>(list)) continue;
    for (int j = 0; j < list->numChildren(); ++j) {
      rviz::Property* row = list->childAt(j);
      if (!kLegendNames.count(row->getName().toStdString())) continue;
      ++rows;
      const QModelIndex name = manager_->getDisplayTreeModel()->indexOf(row);
      const QRect name_cell = tree.visualRect(name),
                  text_cell = tree.visualRect(name.sibling(name.row(), 1));
      EXPECT_LE(metrics.horizontalAdvance(row->getName()) + icon, name_cell.width())
          << row->getName().toStdString() << " in " << name_cell.width() << " px";
      EXPECT_LE(metrics.horizontalAdvance(row->getValue().toString()) + 8, text_cell.width())
          << row->getValue().toString().toStdString() << " in " << text_cell.width() << " px";
    }
  }
  EXPECT_EQ(rows, static_cast<int>(kLegend.size()));
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "legend_reset_test", ros::init_options::AnonymousName);
  QApplication app(argc, argv);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
