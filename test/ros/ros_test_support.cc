// The node's integration tests' shared helpers (ros_test_support.h), compiled once.
#include "test/ros/ros_test_support.h"

namespace mbk_ros_test {

std::string source_path(const std::string& relative) {
  return std::string(MBK_SOURCE_DIR) + "/" + relative;
}

mbk::Model test_model() { return mbk::load_urdf_file(source_path("test/ros/test_robot.urdf")); }

Quadratic::Quadratic(const mbk::Model& model, double phase) : model(&model) {
  c0 = c1 = c2 = Eigen::VectorXd::Zero(model.nq);
  for (int i = 0; i < model.nq; ++i) {
    c0[i] = 0.3 * std::sin(i + 1 + phase);
    c1[i] = 0.5 * std::cos(2 * i + 1 + phase);
    c2[i] = 0.4 * std::sin(3 * i + 2 + phase);
  }
}

mbk::JointState<double> Quadratic::at(double tau) const {
  mbk::JointState<double> s(*model);
  s.position = c0 + c1 * tau + c2 * tau * tau;
  s.velocity = c1 + 2 * c2 * tau;
  s.acceleration = 2 * c2;
  mbk::apply_mimics(*model, s);
  return s;
}

sensor_msgs::JointState joint_state_msg(const mbk::Model& model,
                                        const mbk::JointState<double>& state,
                                        const ros::Time& stamp, bool velocities,
                                        std::vector<std::string> names) {
  if (names.empty()) {
    std::vector<bool> mimic(model.nq, false);
    for (const mbk::Mimic& m : model.mimics) mimic[m.coordinate] = true;
    for (int i = 0; i < model.nq; ++i)
      if (!mimic[i]) names.push_back(model.coordinate_names[i]);
  }
  sensor_msgs::JointState msg;
  msg.header.stamp = stamp;
  for (const std::string& n : names) {
    const int i = model.coordinate_index(n);
    msg.name.push_back(n);
    msg.position.push_back(state.position[i]);
    if (velocities) msg.velocity.push_back(state.velocity[i]);
  }
  return msg;
}

mbk::Data<double> expected_kinematics(const mbk::Model& model,
                                      const mbk::JointState<double>& state) {
  mbk::Data<double> data(model);
  mbk::PartialVelocities<double> pv(model);
  mbk::partial_velocity_kinematics(model, state, pv, data);
  return data;
}

void expect_near(const mbk::Vec3<double>& a, const mbk::Vec3<double>& b, double tol,
                 const std::string& what) {
  EXPECT_LT((a - b).norm(), tol) << what << ": got " << a.transpose() << ", expected "
                                 << b.transpose();
}

void expect_kinematics(const mb_kinematics_msgs::BodyKinematicsArray& msg, const mbk::Model& model,
                       const mbk::Data<double>& d, double tol) {
  ASSERT_EQ(msg.bodies.size(), static_cast<size_t>(model.body_count()));
  EXPECT_EQ(msg.header.frame_id, model.frame);
  for (int k = 1; k <= model.body_count(); ++k) {
    const auto& b = msg.bodies[k - 1];
    const std::string name = model.bodies[k].name;
    EXPECT_EQ(b.name, name);
    EXPECT_EQ(b.index, static_cast<uint32_t>(k));
    EXPECT_EQ(b.lower_body, static_cast<uint32_t>(model.bodies[k].lower));
    expect_near(vec(b.pose.position), d.origin[k], tol, name + " origin");
    const Eigen::Quaterniond q(b.pose.orientation.w, b.pose.orientation.x, b.pose.orientation.y,
                               b.pose.orientation.z);
    EXPECT_LT((q.toRotationMatrix() - d.rotation[k]).norm(), tol) << name << " rotation";
    expect_near(vec(b.mass_center), d.mass_center[k], tol, name + " mass center");
    expect_near(vec(b.twist.angular), d.omega[k], tol, name + " omega");
    expect_near(vec(b.twist.linear), d.mass_center_velocity[k], tol, name + " velocity");
    expect_near(vec(b.accel.angular), d.alpha[k], tol, name + " alpha");
    expect_near(vec(b.accel.linear), d.mass_center_acceleration[k], tol, name + " acceleration");
  }
}

bool wait_until(const std::function<bool()>& done, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

bool latched_lower_body_array(ros::NodeHandle& nh, mb_kinematics_msgs::LowerBodyArray& topology,
                              double seconds) {
  bool got = false;
  ros::Subscriber sub = nh.subscribe<mb_kinematics_msgs::LowerBodyArray>(
      "lower_body_array", 1, [&](const mb_kinematics_msgs::LowerBodyArray::ConstPtr& m) {
        topology = *m;
        got = true;
      });
  return wait_until([&] { return got; }, seconds);
}

KinematicsRecorder::KinematicsRecorder(ros::NodeHandle& nh, const std::string& topic)
    : sub_(nh.subscribe(topic, 100, &KinematicsRecorder::on_message, this)) {}

bool KinematicsRecorder::connected() const { return sub_.getNumPublishers() > 0; }

std::vector<mb_kinematics_msgs::BodyKinematicsArray> KinematicsRecorder::at(
    const ros::Time& stamp) const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<mb_kinematics_msgs::BodyKinematicsArray> out;
  for (const auto& m : messages_)
    if (m.header.stamp == stamp) out.push_back(m);
  return out;
}

size_t KinematicsRecorder::count() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return messages_.size();
}

mb_kinematics_msgs::BodyKinematicsArray KinematicsRecorder::latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return messages_.back();
}

bool KinematicsRecorder::wait_for(const ros::Time& stamp, double seconds) const {
  return wait_until([&] { return !at(stamp).empty(); }, seconds);
}

void KinematicsRecorder::on_message(const mb_kinematics_msgs::BodyKinematicsArray& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  messages_.push_back(msg);
}

void connect(const ros::Publisher& pub, const KinematicsRecorder& recorder) {
  ASSERT_TRUE(wait_until([&] { return pub.getNumSubscribers() > 0 && recorder.connected(); }, 10))
      << "the node did not connect";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
}

TfRecorder::TfRecorder(ros::NodeHandle& nh)
    : tf_(nh.subscribe("/tf", 1000, &TfRecorder::on, this)),
      tf_static_(nh.subscribe("/tf_static", 100, &TfRecorder::on, this)) {}

int TfRecorder::publishers() const { return tf_.getNumPublishers(); }

std::map<std::string, std::set<std::string>> TfRecorder::by_publisher() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return by_publisher_;
}

std::map<std::string, std::set<std::string>> TfRecorder::by_child() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return by_child_;
}

void TfRecorder::on(const ros::MessageEvent<tf2_msgs::TFMessage const>& e) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& t : e.getMessage()->transforms) {
    by_publisher_[e.getPublisherName()].insert(t.header.frame_id + " -> " + t.child_frame_id);
    by_child_[t.child_frame_id].insert(e.getPublisherName() + ": " + t.header.frame_id);
  }
}

Transforms::Transforms(ros::NodeHandle& nh, const std::string& topic, bool latched)
    : latched_(latched), sub_(nh.subscribe(topic, 1000, &Transforms::on, this)) {}

bool Transforms::connected() const { return sub_.getNumPublishers() > 0; }

std::map<Key, geometry_msgs::TransformStamped> Transforms::get() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return transforms_;
}

void Transforms::on(const tf2_msgs::TFMessage& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& t : msg.transforms)
    transforms_[{t.child_frame_id, latched_ ? 0.0 : t.header.stamp.toSec()}] = t;
}

nav_msgs::Odometry odometry_msg(const std::string& frame, const ros::Time& stamp,
                                const mbk::Vec3<double>& p, const Eigen::Quaterniond& q,
                                const mbk::Vec3<double>& v, const mbk::Vec3<double>& w) {
  nav_msgs::Odometry o;
  o.header.stamp = stamp;
  o.header.frame_id = frame;
  o.child_frame_id = "base_link";
  const auto set = [](auto& m, const mbk::Vec3<double>& x) {
    m.x = x.x();
    m.y = x.y();
    m.z = x.z();
  };
  set(o.pose.pose.position, p);
  o.pose.pose.orientation.w = q.w();
  set(o.pose.pose.orientation, q.vec());
  set(o.twist.twist.linear, q.conjugate() * v);
  set(o.twist.twist.angular, q.conjugate() * w);
  return o;
}

int run_node(const std::string& arguments, std::string& output) {
  const std::string command = std::string(MBK_NODE_PATH) + " " + arguments + " 2>&1 > /dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace mbk_ros_test
