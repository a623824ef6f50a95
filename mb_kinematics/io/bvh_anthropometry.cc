#include "mb_kinematics/io/bvh_anthropometry.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/bvh_bones.h"
#include "mb_kinematics/io/name_list.h"

namespace mbk {
namespace {

enum Row {
  kHead,
  kUpperTrunk,
  kMiddleTrunk,
  kLowerTrunk,
  kUpperArm,
  kForearm,
  kHand,
  kThigh,
  kShank,
  kFoot,
  kRows
};
constexpr double kPercent = 0.01;
// The three trunk parts' lengths in mm (Table 4; upper, middle, lower; male, female): they place
// XYPH and OMPH on the line from SUPR to MIDH.
constexpr double kTrunkPartLength[2][3] = {{170.7, 215.5, 145.7}, {142.5, 205.3, 181.5}};
const char* const kTrunkKeys[3] = {"upper_trunk", "middle_trunk", "lower_trunk"};
const char kIncomplete[] =
    "whole-body outputs incomplete (system_incomplete in the CSV, system.missing_segments in the "
    "bag, \"incomplete\" in mbk eval's JSON; --segments FILE maps joints to segments): segments "
    "not found, their mass spread over the others: ";

// A segment on one side of the body: 0 none (head, trunk), 1 left, 2 right.
struct Found {
  int row;
  int side;
  int body;                       // index in BvhFile::segments that carries it
  Vec3<double> proximal, distal;  // rest pose, in R (mass center measured from `proximal`)
};

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return text;
}

// The side a joint's name gives (0 none, 1 left, 2 right) and its part: lowercase, without a
// namespace (Mixamo's "mixamorig:"), the side and separators (_ . - and spaces). Sides: a
// prefix Left/Right, L_/R_, L./R. (any case), a suffix _L/_R, .L/.R, Left/Right (any case), or
// L/R before a capital (CMU's LThumb). "mixamorig:LeftUpLeg" -> 1, "upleg"; "UpperArm_L" -> 1,
// "upperarm"; "forearm.R" -> 2, "forearm"; "LThumb" -> 1, "thumb"; "Head" -> 0, "head".
std::pair<int, std::string> side_and_part(std::string name) {
  name = name.substr(name.rfind(':') + 1);
  const std::string lower = lowercase(name);
  static const std::pair<std::string, int> kPrefixes[] = {{"left", 1}, {"right", 2}, {"l_", 1},
                                                          {"r_", 2},   {"l.", 1},    {"r.", 2}};
  static const std::pair<std::string, int> kSuffixes[] = {{"_l", 1}, {"_r", 2},   {".l", 1},
                                                          {".r", 2}, {"left", 1}, {"right", 2}};
  int side = 0;
  std::string rest = lower;
  for (const auto& [prefix, s] : kPrefixes)
    if (!side && lower.size() > prefix.size() && lower.compare(0, prefix.size(), prefix) == 0)
      side = s, rest = lower.substr(prefix.size());
  for (const auto& [suffix, s] : kSuffixes)
    if (!side && lower.size() > suffix.size() &&
        lower.compare(lower.size() - suffix.size(), suffix.size(), suffix) == 0)
      side = s, rest = lower.substr(0, lower.size() - suffix.size());
  if (!side && name.size() > 1 && (name[0] == 'L' || name[0] == 'R') && std::isupper(name[1]))
    side = name[0] == 'L' ? 1 : 2, rest = lower.substr(1);
  std::string part;
  for (char c : rest)
    if (c != '_' && c != '.' && c != '-' && c != ' ') part += c;
  return {side, part};
}

// The skeleton in its rest pose (every angle 0: every body's axes are R's).
class Skeleton {
 public:
  Skeleton(const BvhFile& bvh, double scale, const SegmentMap& map)
      : bvh_(bvh), scale_(scale), fixed_(fixed_in_space(bvh)) {
    const size_t n = bvh.segments.size();
    origin_.resize(n);
    children_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const int parent = bvh.segments[i].parent;
      origin_[i] =
          scale * bvh.segments[i].offset + (parent < 0 ? Vec3<double>::Zero() : origin_[parent]);
      if (parent >= 0) children_[parent].push_back(static_cast<int>(i));
      index_[bvh.segments[i].name] = static_cast<int>(i);
    }
    for (const auto& [segment, entry] : map.segment) mapped_[segment] = resolve(map, entry);
  }
  // The segment the user's map gives `key` (bvh_segment_map.h), or -1.
  int mapped(const std::string& key) const {
    const auto it = mapped_.find(key);
    return it == mapped_.end() ? -1 : it->second.body;
  }
  // The map's proximal (or `distal`) end of `key`, else `rule`.
  Vec3<double> end(const std::string& key, bool distal, const Vec3<double>& rule) const {
    const auto it = mapped_.find(key);
    if (it == mapped_.end()) return rule;
    const std::optional<Vec3<double>>& p = distal ? it->second.distal : it->second.proximal;
    return p ? *p : rule;
  }
  // The joint whose origin the map gives as that end, or -1 (no such end, a mean, an End Site).
  int end_joint(const std::string& key, bool distal) const {
    const auto it = mapped_.find(key);
    if (it == mapped_.end()) return -1;
    return distal ? it->second.distal_joint : it->second.proximal_joint;
  }
  int size() const { return static_cast<int>(origin_.size()); }
  int parent(int i) const { return bvh_.segments[i].parent; }
  const Vec3<double>& origin(int i) const { return origin_[i]; }
  const std::vector<int>& children(int i) const { return children_[i]; }
  const std::string& name(int i) const { return bvh_.segments[i].name; }
  // Stays where it is in R through the motion (bvh_bones.h): it carries no moving segment.
  bool fixed(int i) const { return fixed_[i]; }

  // The first segment named `side` + one of `parts` (side_and_part), or -1.
  int find(int side, std::initializer_list<const char*> parts) const {
    for (int i = 0; i < size(); ++i) {
      const auto sp = side_and_part(name(i));
      if (sp.first != side) continue;
      for (const char* p : parts)
        if (sp.second == p) return i;
    }
    return -1;
  }
  // The children's origins' mean, else the End Site, else the origin.
  Vec3<double> tip(int i) const {
    if (!children_[i].empty()) {
      Vec3<double> sum = Vec3<double>::Zero();
      for (int c : children_[i]) sum += origin_[c];
      return sum / children_[i].size();
    }
    const BvhSegment& s = bvh_.segments[i];
    return s.has_end_site ? Vec3<double>(origin_[i] + scale_ * s.end_site) : origin_[i];
  }
  // The point of i's subtree (origins and End Sites) farthest from `from`.
  Vec3<double> farthest(int i, const Vec3<double>& from) const {
    Vec3<double> best = tip(i);
    for (int j = i; j < size(); ++j) {
      if (!in_subtree(j, i)) continue;
      for (const Vec3<double>& p : {origin_[j], tip(j)})
        if ((p - from).norm() > (best - from).norm()) best = p;
    }
    return best;
  }
  // A body without children whose End Site is at OFFSET 0 0 0: its tip is its own origin.
  bool zero_end_site(int i) const {
    const BvhSegment& b = bvh_.segments[i];
    return children_[i].empty() && b.has_end_site && b.end_site.isZero();
  }
  bool in_subtree(int j, int root) const {
    while (j > root) j = parent(j);
    return j == root;
  }

 private:
  const BvhFile& bvh_;
  double scale_;
  std::vector<bool> fixed_;
  std::vector<Vec3<double>> origin_;
  std::vector<std::vector<int>> children_;
  // A segment of the user's map, its names resolved: the body that carries it (-1: the
  // rules'), its ends in the rest pose, and the joints that are those ends (-1: none).
  struct Mapped {
    int body = -1;
    std::optional<Vec3<double>> proximal, distal;
    int proximal_joint = -1, distal_joint = -1;
  };
  int joint_index(const SegmentMap& map, const std::string& joint) const {
    const auto it = index_.find(joint);
    if (it == index_.end())
      throw std::invalid_argument(
          printable(map.path + ": joint " + joint + " is not in " + bvh_.path));
    return it->second;
  }
  Vec3<double> point(const SegmentMap& map, const MapPoint& p, int line) const {
    Vec3<double> sum = Vec3<double>::Zero();
    for (const std::string& joint : p.joints) {
      const int i = joint_index(map, joint);
      if (p.end_site && !bvh_.segments[i].has_end_site)
        throw std::invalid_argument(printable(map.path + ":" + std::to_string(line) + ": " + joint +
                                              " has no End Site in " + bvh_.path));
      sum +=
          p.end_site ? Vec3<double>(origin_[i] + scale_ * bvh_.segments[i].end_site) : origin_[i];
    }
    return sum / static_cast<double>(p.joints.size());
  }
  Mapped resolve(const SegmentMap& map, const MappedSegment& entry) const {
    Mapped m;
    if (!entry.joint.empty()) m.body = joint_index(map, entry.joint);
    auto single = [&](const MapPoint& p) {
      return p.joints.size() == 1 && !p.end_site ? joint_index(map, p.joints[0]) : -1;
    };
    if (entry.proximal) {
      m.proximal = point(map, *entry.proximal, entry.line);
      m.proximal_joint = single(*entry.proximal);
    }
    if (entry.distal) {
      m.distal = point(map, *entry.distal, entry.line);
      m.distal_joint = single(*entry.distal);
    }
    return m;
  }

  std::unordered_map<std::string, int> index_;      // name -> segment
  std::unordered_map<std::string, Mapped> mapped_;  // segment key -> its map entry
};

// The parent of `child` in a limb; -1 if `child` is missing or the root.
int limb_parent(const Skeleton& s, int child) { return child > 0 ? s.parent(child) : -1; }

// Upper arm, forearm, hand and thigh, shank, foot of one side, each the user's map's if it
// names it, else found from the hand (Hand or Wrist; without one, from the forearm: ForeArm,
// LowerArm or Elbow) and the foot (Foot or Ankle; else the shank: Leg, LowerLeg, Shin or Knee)
// upwards.
void find_limbs(const Skeleton& s, int side, std::vector<Found>& found) {
  const std::string prefix = side == 1 ? "left_" : "right_";
  auto pick = [&](const char* part, int rule) {
    const int m = s.mapped(prefix + part);
    return m > 0 ? m : rule;
  };
  const int hand = pick("hand", s.find(side, {"hand", "wrist"}));
  const int forearm = pick(
      "forearm", hand > 0 ? limb_parent(s, hand) : s.find(side, {"forearm", "lowerarm", "elbow"}));
  const int upper_arm = pick("upper_arm", limb_parent(s, forearm));
  const int foot = pick("foot", s.find(side, {"foot", "ankle"}));
  const int shank = pick(
      "shank", foot > 0 ? limb_parent(s, foot) : s.find(side, {"leg", "lowerleg", "shin", "knee"}));
  const int thigh = pick("thigh", limb_parent(s, shank));
  // A segment ends at the next one's joint; without one (a hand or foot the tables do not name),
  // at its own tip; the map's ends where it gives them.
  auto add = [&](int row, const char* part, int body, int next) {
    if (body <= 0) return;
    const std::string key = prefix + part;
    const Vec3<double> proximal = s.end(key, false, s.origin(body));
    Vec3<double> distal = next > 0 ? s.origin(next) : s.tip(body);
    if (row == kFoot) distal = s.farthest(body, proximal);
    found.push_back({row, side, body, proximal, s.end(key, true, distal)});
  };
  add(kUpperArm, "upper_arm", upper_arm, forearm);
  add(kForearm, "forearm", forearm, hand);
  add(kHand, "hand", hand, -1);
  add(kThigh, "thigh", thigh, shank);
  add(kShank, "shank", shank, foot);
  add(kFoot, "foot", foot, -1);
}

const Found* find_row(const std::vector<Found>& found, int row, int side) {
  for (const Found& f : found)
    if (f.row == row && f.side == side) return &f;
  return nullptr;
}

// The lowest joint named *neck* above the head (CMU's Neck, cgspeed's lowerneck; the head itself
// if none): its origin stands for CERV/SUPR.
int cervical(const Skeleton& s, int head) {
  int c = head;
  while (c > 0 && side_and_part(s.name(s.parent(c))).second.find("neck") != std::string::npos)
    c = s.parent(c);
  return c;
}

// Head and neck from VERT (the head's farthest point) to CERV; the trunk's three parts on the
// line from MIDH (mid-hip: between the thighs, else the root) to CERV, each on the spine body
// whose span along that line holds its mass center (doc/anthropometry.md).
void find_head_and_trunk(const Skeleton& s, Sex sex, std::vector<Found>& found) {
  const int head = s.mapped("head") > 0 ? s.mapped("head") : s.find(0, {"head"});
  if (head <= 0) return;
  // CERV: the map's head distal end, else its upper trunk's proximal one (SUPR, which the
  // rules take at CERV), else the lowest neck joint.
  int neck = s.end_joint("head", true);
  if (neck < 0) neck = s.end_joint("upper_trunk", false);
  if (neck < 0) neck = cervical(s, head);
  const Vec3<double> cerv = s.end("head", true, s.end("upper_trunk", false, s.origin(neck)));
  found.push_back({kHead, 0, head, s.end("head", false, s.farthest(head, cerv)), cerv});
  // The root up to the neck's parent, without the bodies fixed in space while others move (a
  // static ROOT under the pelvis): a static body never carries a moving segment.
  std::vector<int> spine, moving;
  for (int b = s.parent(neck); b >= 0; b = s.parent(b)) spine.insert(spine.begin(), b);
  for (int b : spine)
    if (!s.fixed(b)) moving.push_back(b);
  if (!moving.empty()) spine = moving;
  if (spine.empty()) return;  // the neck is the root: no trunk below it
  const Found* left = find_row(found, kThigh, 1);
  const Found* right = find_row(found, kThigh, 2);
  const Vec3<double> midh = s.end(
      "lower_trunk", true,
      left && right ? Vec3<double>((left->proximal + right->proximal) / 2) : s.origin(spine[0]));
  const Vec3<double> supr = s.end("upper_trunk", false, cerv);
  const Vec3<double> line = supr - midh;
  const double* part = kTrunkPartLength[static_cast<int>(sex)];
  const double total = part[0] + part[1] + part[2];
  const Vec3<double> xyph = supr - line * (part[0] / total);
  const Vec3<double> omph = midh + line * (part[2] / total);
  const Vec3<double> ends[3][2] = {{supr, xyph}, {xyph, omph}, {omph, midh}};
  for (int i = 0; i < 3; ++i) {
    const SegmentRow& row = de_leva_table()[kUpperTrunk + i];
    const Vec3<double> c =
        ends[i][0] + row.mass_center[static_cast<int>(sex)] * kPercent * (ends[i][1] - ends[i][0]);
    const double t = (c - midh).dot(line) / line.squaredNorm();
    int body = spine.front();
    for (int b : spine)
      if ((s.origin(b) - midh).dot(line) / line.squaredNorm() <= t) body = b;
    const int m = s.mapped(kTrunkKeys[i]);
    found.push_back({kUpperTrunk + i, 0, m >= 0 ? m : body, ends[i][0], ends[i][1]});
  }
}

// Anatomical directions in the rest pose: up (MIDH to CERV, else +y) and lateral (right to left
// thigh, else upper arm, else +x), made orthogonal.
struct Directions {
  Vec3<double> up, lateral, forward;
};

Directions directions_of(const std::vector<Found>& found) {
  Directions d{Vec3<double>::UnitY(), Vec3<double>::UnitX(), Vec3<double>::Zero()};
  const Found* trunk = find_row(found, kLowerTrunk, 0);
  const Found* head = find_row(found, kHead, 0);
  if (trunk && head && (head->distal - trunk->distal).norm() > 0)
    d.up = (head->distal - trunk->distal).normalized();
  for (int row : {kThigh, kUpperArm}) {
    const Found* l = find_row(found, row, 1);
    const Found* r = find_row(found, row, 2);
    if (!l || !r) continue;
    const Vec3<double> across = l->proximal - r->proximal;
    if ((across - across.dot(d.up) * d.up).norm() <= 0) continue;
    d.lateral = across;
    break;
  }
  d.lateral = (d.lateral - d.lateral.dot(d.up) * d.up).normalized();
  d.forward = d.lateral.cross(d.up);
  return d;
}

// The central inertia of a segment of mass m from its radii of gyration: longitudinal about the
// segment's line, sagittal about the forward axis across it, transverse about the third (for a
// segment along the forward axis, the foot: transverse about the lateral axis).
Mat3<double> segment_inertia(const SegmentRow& row, int sex, double m, const Found& f,
                             const Directions& d) {
  const Vec3<double> along = f.distal - f.proximal;
  const double length = along.norm();
  if (length == 0) return Mat3<double>::Zero();
  const Vec3<double> u = along / length;
  Vec3<double> sagittal = d.forward - d.forward.dot(u) * u;
  Vec3<double> transverse;
  if (sagittal.norm() > 0.5) {
    sagittal.normalize();
    transverse = u.cross(sagittal);
  } else {
    transverse = (d.lateral - d.lateral.dot(u) * u).normalized();
    sagittal = transverse.cross(u);
  }
  auto moment = [&](const double* r, const Vec3<double>& axis) -> Mat3<double> {
    const double k = r[sex] * kPercent * length;
    return m * k * k * axis * axis.transpose();
  };
  return moment(row.sagittal, sagittal) + moment(row.transverse, transverse) +
         moment(row.longitudinal, u);
}

// Bodies no segment accounts for: not carrying one, not in a hand's, foot's or head's subtree,
// not on the spine or the neck, not between the trunk and a limb (hip joints, clavicles).
std::vector<std::string> uncovered(const Skeleton& s, const std::vector<Found>& found) {
  std::vector<bool> covered(s.size(), false);
  for (const Found& f : found) {
    covered[f.body] = true;
    if (f.row == kHand || f.row == kFoot || f.row == kHead)
      for (int j = f.body; j < s.size(); ++j) covered[j] = covered[j] || s.in_subtree(j, f.body);
  }
  for (const Found& f : found) {  // up from each segment to the first covered body
    for (int b = s.parent(f.body); b >= 0 && !covered[b]; b = s.parent(b)) covered[b] = true;
  }
  std::vector<std::string> names;
  for (int i = 0; i < s.size(); ++i)
    if (!covered[i]) names.push_back(s.name(i));
  return names;
}

std::vector<Found> find_segments(const Skeleton& s, Sex sex) {
  std::vector<Found> found;
  for (int side : {1, 2}) find_limbs(s, side, found);
  find_head_and_trunk(s, sex, found);
  return found;
}

std::vector<std::string> missing_rows(const std::vector<Found>& found) {
  static const char* const kSide[] = {"", "left ", "right "};
  std::vector<std::string> names;
  for (int row = 0; row < kRows; ++row) {
    const bool limb = row >= kUpperArm;
    for (int side = limb ? 1 : 0; side <= (limb ? 2 : 0); ++side)
      if (!find_row(found, row, side))
        names.push_back(kSide[side] + std::string(de_leva_table()[row].name));
  }
  return names;
}

// "" or one note: the segments that end at a tip (hand, foot, head's vertex) which is an End
// Site at OFFSET 0 0 0 (Bandai Namco's hands, head and toes), so end at that joint: shorter
// than the body, the mass center on the joint (a hand) or below the vertex (a head).
std::string zero_end_site_note(const Skeleton& s, const std::vector<Found>& found) {
  static const char* const kSide[] = {"", "left ", "right "};
  std::vector<std::string> segments, joints;
  for (const Found& f : found) {
    if (f.row != kHand && f.row != kFoot && f.row != kHead) continue;
    const Vec3<double>& tip = f.row == kHead ? f.proximal : f.distal;
    for (int j = f.body; j < s.size(); ++j) {
      if (!s.in_subtree(j, f.body) || !s.zero_end_site(j) || s.origin(j) != tip) continue;
      segments.push_back(kSide[f.side] + std::string(de_leva_table()[f.row].name));
      joints.push_back(s.name(j));
      break;
    }
  }
  if (segments.empty()) return "";
  return "End Sites at OFFSET 0 0 0 (" + name_list(joints) + "): " + name_list(segments) +
         " end at that joint, not at the body's tip, so their mass centers lie on the joint or "
         "short of the tip (--segments FILE gives other ends, doc/anthropometry.md)";
}

// A segment's mass, mass center (rest pose, in R) and central inertia, on the body carrying it.
struct Part {
  int body;
  double mass;
  Vec3<double> center;
  Mat3<double> inertia;
};

// de Leva's segments: each found segment's share of body_mass (the fractions of the segments not
// found spread over the found ones in proportion), its mass center and central inertia.
std::vector<Part> de_leva_parts(const std::vector<Found>& found, double body_mass, Sex sex,
                                const Directions& d) {
  const int x = static_cast<int>(sex);
  double fraction_found = 0;
  for (const Found& f : found) fraction_found += de_leva_table()[f.row].mass[x];
  std::vector<Part> parts;
  for (const Found& f : found) {
    const SegmentRow& row = de_leva_table()[f.row];
    const double m = body_mass * row.mass[x] / fraction_found;
    parts.push_back({f.body, m,
                     f.proximal + row.mass_center[x] * kPercent * (f.distal - f.proximal),
                     segment_inertia(row, x, m, f, d)});
  }
  return parts;
}

// The row of dempster_table() for a de Leva row: the three trunk parts are Dempster's one trunk.
const DempsterRow& dempster_row(int row) {
  static const int kRowOf[kRows] = {0, 1, 1, 1, 2, 3, 4, 5, 6, 7};
  return dempster_table()[kRowOf[row]];
}

bool is_trunk(int row) { return row == kUpperTrunk || row == kMiddleTrunk || row == kLowerTrunk; }

// Central inertia `inertia` of mass m at `from` moved to the point `to` (parallel axes).
Mat3<double> moved(double m, const Mat3<double>& inertia, const Vec3<double>& from,
                   const Vec3<double>& to) {
  const Vec3<double> r = from - to;
  return inertia + m * (r.squaredNorm() * Mat3<double>::Identity() - r * r.transpose());
}

// Dempster's trunk, from the greater trochanters (MIDH, where the lower trunk part ends) to the
// glenohumeral joints (the upper arms' origins, else SUPR), its center at `c` on the body
// carrying the de Leva trunk part nearest it; its central inertia de Leva's parts' about `c`,
// times the mass ratio. Returns false without a trunk part.
bool dempster_trunk(const std::vector<Found>& found, const std::vector<Part>& leva, double fraction,
                    Part& trunk) {
  const Found *lower = find_row(found, kLowerTrunk, 0), *upper = find_row(found, kUpperTrunk, 0);
  const Found *left = find_row(found, kUpperArm, 1), *right = find_row(found, kUpperArm, 2);
  if (!lower || !upper) return false;
  const Vec3<double> gh =
      left && right ? Vec3<double>((left->proximal + right->proximal) / 2) : upper->proximal;
  const DempsterRow& row = dempster_row(kUpperTrunk);
  trunk = {lower->body, fraction * row.mass, Vec3<double>::Zero(), Mat3<double>::Zero()};
  trunk.center = lower->distal + row.mass_center * (gh - lower->distal);
  double leva_mass = 0, nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < found.size(); ++i) {
    if (!is_trunk(found[i].row)) continue;
    leva_mass += leva[i].mass;
    trunk.inertia += moved(leva[i].mass, leva[i].inertia, leva[i].center, trunk.center);
    const double distance = (leva[i].center - trunk.center).norm();
    if (distance < nearest) nearest = distance, trunk.body = leva[i].body;
  }
  trunk.inertia *= trunk.mass / leva_mass;
  return true;
}

// Dempster's segments (Winter's Table 4.1) on the bodies de Leva's found: the same joint ends for
// the limbs but the foot (ankle to the toe joint, the foot's tip, for the head of metatarsal II);
// the head and neck from CERV to the head joint's origin (for the ear canal, where its center
// is); one trunk (dempster_trunk). Masses shared as de Leva's; each central inertia de Leva's
// times the mass ratio.
std::vector<Part> dempster_parts(const Skeleton& s, const std::vector<Found>& found,
                                 const std::vector<Part>& leva, double body_mass) {
  double fraction_found = 0;
  bool trunk_found = false;
  for (const Found& f : found) {
    if (is_trunk(f.row) && trunk_found) continue;
    trunk_found = trunk_found || is_trunk(f.row);
    fraction_found += dempster_row(f.row).mass;
  }
  const double fraction = body_mass / fraction_found;
  std::vector<Part> parts;
  for (size_t i = 0; i < found.size(); ++i) {
    const Found& f = found[i];
    if (is_trunk(f.row)) continue;
    const DempsterRow& row = dempster_row(f.row);
    Vec3<double> proximal = f.proximal, distal = f.distal;
    if (f.row == kHead) proximal = f.distal, distal = s.origin(f.body);
    if (f.row == kFoot) distal = s.tip(f.body);
    const double m = fraction * row.mass;
    parts.push_back({f.body, m, proximal + row.mass_center * (distal - proximal),
                     leva[i].inertia * (m / leva[i].mass)});
  }
  Part trunk;
  if (dempster_trunk(found, leva, fraction, trunk)) parts.push_back(trunk);
  return parts;
}

// Mass, mass center (in R, rest pose) and central inertia gathered on one body.
struct Lumped {
  double mass = 0;
  Vec3<double> moment = Vec3<double>::Zero();  // sum of m_i c_i
  std::vector<std::pair<double, Vec3<double>>> parts;
  Mat3<double> inertia = Mat3<double>::Zero();  // sum of the parts' central inertias
};

}  // namespace

Sex sex_from_string(const std::string& text) {
  if (text == "male" || text == "m") return Sex::kMale;
  if (text == "female" || text == "f") return Sex::kFemale;
  throw std::invalid_argument("sex: '" + text + "' is neither male nor female (de Leva's columns)");
}

const std::vector<SegmentRow>& de_leva_table() {
  // Percent, as printed in Table 4; head and neck from its lower part (VERT to CERV).
  static const std::vector<SegmentRow> table = {
      {"head and neck",
       "VERT",
       "CERV",
       {6.94, 6.68},
       {50.02, 48.41},
       {30.3, 27.1},
       {31.5, 29.5},
       {26.1, 26.1}},
      {"upper trunk",
       "SUPR",
       "XYPH",
       {15.96, 15.45},
       {29.99, 20.77},
       {71.6, 74.6},
       {45.4, 50.2},
       {65.9, 71.8}},
      {"middle trunk",
       "XYPH",
       "OMPH",
       {16.33, 14.65},
       {45.02, 45.12},
       {48.2, 43.3},
       {38.3, 35.4},
       {46.8, 41.5}},
      {"lower trunk",
       "OMPH",
       "MIDH",
       {11.17, 12.47},
       {61.15, 49.20},
       {61.5, 43.3},
       {55.1, 40.2},
       {58.7, 44.4}},
      {"upper arm",
       "SJC",
       "EJC",
       {2.71, 2.55},
       {57.72, 57.54},
       {28.5, 27.8},
       {26.9, 26.0},
       {15.8, 14.8}},
      {"forearm",
       "EJC",
       "WJC",
       {1.62, 1.38},
       {45.74, 45.59},
       {27.6, 26.1},
       {26.5, 25.7},
       {12.1, 9.4}},
      {"hand",
       "WJC",
       "MET3",
       {0.61, 0.56},
       {79.00, 74.74},
       {62.8, 53.1},
       {51.3, 45.4},
       {40.1, 33.5}},
      {"thigh",
       "HJC",
       "KJC",
       {14.16, 14.78},
       {40.95, 36.12},
       {32.9, 36.9},
       {32.9, 36.4},
       {14.9, 16.2}},
      {"shank",
       "KJC",
       "LMAL",
       {4.33, 4.81},
       {44.59, 44.16},
       {25.5, 27.1},
       {24.9, 26.7},
       {10.3, 9.3}},
      {"foot",
       "HEEL",
       "TTIP",
       {1.37, 1.29},
       {44.15, 40.14},
       {25.7, 29.9},
       {24.5, 27.9},
       {12.4, 13.9}},
  };
  return table;
}

SegmentTable segment_table_from_string(const std::string& text) {
  if (text == "de_leva" || text == "deleva") return SegmentTable::kDeLeva;
  if (text == "dempster") return SegmentTable::kDempster;
  throw std::invalid_argument("anthropometry: '" + printable(text) +
                              "' is neither de_leva nor dempster");
}

const std::vector<DempsterRow>& dempster_table() {
  // Winter (2009), Table 4.1, "Segment weight / total body weight" and "center of mass / segment
  // length, proximal"; the trunk from the greater trochanter to the glenohumeral joint.
  static const std::vector<DempsterRow> table = {
      {"head and neck", "C7-T1 and first rib", "ear canal", 0.081, 1.000},
      {"trunk", "greater trochanter", "glenohumeral joint", 0.497, 0.50},
      {"upper arm", "glenohumeral axis", "elbow axis", 0.028, 0.436},
      {"forearm", "elbow axis", "ulnar styloid", 0.016, 0.430},
      {"hand", "wrist axis", "knuckle II middle finger", 0.006, 0.506},
      {"thigh", "greater trochanter", "femoral condyles", 0.100, 0.433},
      {"leg", "femoral condyles", "medial malleolus", 0.0465, 0.433},
      {"foot", "lateral malleolus", "head metatarsal II", 0.0145, 0.50},
  };
  return table;
}

double dempster_mass_sum() {
  double sum = 0;
  for (size_t row = 0; row < dempster_table().size(); ++row)
    sum += (row >= 2 ? 2 : 1) * dempster_table()[row].mass;
  return sum;
}

double de_leva_mass_sum(Sex sex) {
  double sum = 0;
  for (size_t row = 0; row < de_leva_table().size(); ++row)
    sum += (row >= kUpperArm ? 2 : 1) * de_leva_table()[row].mass[static_cast<int>(sex)];
  return sum * kPercent;
}

std::vector<std::string> set_segment_parameters(const BvhFile& bvh, double scale, double body_mass,
                                                Sex sex, Model& model, const SegmentMap& map,
                                                SegmentTable table) {
  if (!(body_mass > 0) || !std::isfinite(body_mass))
    throw std::invalid_argument("body mass: must be a positive number of kg");
  const Skeleton s(bvh, scale, map);
  const std::vector<Found> found = find_segments(s, sex);
  std::vector<Part> parts = de_leva_parts(found, body_mass, sex, directions_of(found));
  if (table == SegmentTable::kDempster) parts = dempster_parts(s, found, parts, body_mass);
  std::vector<Lumped> lumped(s.size());
  for (const Part& p : parts) {
    Lumped& l = lumped[p.body];
    l.mass += p.mass;
    l.moment += p.mass * p.center;
    l.parts.push_back({p.mass, p.center});
    l.inertia += p.inertia;
  }
  for (int i = 0; i < s.size(); ++i) {
    Lumped& l = lumped[i];
    if (l.mass == 0) continue;
    const Vec3<double> c = l.moment / l.mass;
    for (const auto& [m, ci] : l.parts) {  // parallel axes (Steiner)
      const Vec3<double> r = ci - c;
      l.inertia += m * (r.squaredNorm() * Mat3<double>::Identity() - r * r.transpose());
    }
    Body& body = model.bodies[i + 1];
    body.mass = l.mass;
    body.mass_center = c - s.origin(i);  // body axes are R's in the rest pose
    body.inertia = l.inertia;
    body.has_inertia = true;
  }
  std::vector<std::string> notes;
  const std::vector<std::string> massless = uncovered(s, found);
  if (!massless.empty())
    notes.push_back(
        bvh.path + ": segment parameters (" +
        (table == SegmentTable::kDempster ? "Dempster, Winter Table 4.1" : "de Leva 1996") +
        "): massless, in no table " + "segment: " + name_list(massless));
  const std::string zero_ends = zero_end_site_note(s, found);
  if (!zero_ends.empty()) notes.push_back(bvh.path + ": " + zero_ends);
  const std::vector<std::string> missing = missing_rows(found);
  if (!missing.empty()) notes.push_back(bvh.path + ": " + kIncomplete + name_list(missing));
  return notes;
}

std::vector<std::string> missing_segments(const BvhFile& bvh, double scale, const SegmentMap& map) {
  return missing_rows(find_segments(Skeleton(bvh, scale, map), Sex::kMale));
}

}  // namespace mbk
