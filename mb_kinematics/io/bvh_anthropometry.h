// Segment masses, mass centers and inertias of a BVH skeleton from de Leva (1996), "Adjustments
// to Zatsiorsky-Seluyanov's segment inertia parameters", J. Biomech. 29(9):1223-1230, Table 4,
// for a given body mass and sex (doc/anthropometry.md: the table as used, the naming map, the
// rules). ROS-free.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_segment_map.h"

namespace mbk {

enum class Sex { kMale, kFemale };

// "male"/"female" (also "m"/"f"); std::invalid_argument naming the text otherwise.
Sex sex_from_string(const std::string& text);

// One row of de Leva's Table 4: the mass as a fraction of the body's, the mass center's distance
// from the `proximal` landmark as a fraction of the segment's length (proximal to distal), and
// the radii of gyration about the sagittal, transverse and longitudinal axes through the mass
// center as fractions of the length. Index [0] male, [1] female.
struct SegmentRow {
  const char* name;
  const char* proximal;  // the landmark the mass center is measured from
  const char* distal;
  double mass[2];
  double mass_center[2];
  double sagittal[2];
  double transverse[2];
  double longitudinal[2];
};

// The rows used (head and neck, upper/middle/lower trunk, upper arm, forearm, hand, thigh,
// shank, foot), one per segment; limbs appear once and count twice (left and right).
const std::vector<SegmentRow>& de_leva_table();
// The sum of every segment's mass fraction, limbs counted twice: 1 up to the table's rounding.
double de_leva_mass_sum(Sex sex);

// The segment parameter table: de Leva (1996, the default) or Dempster (1955) as tabulated in
// Winter, Biomechanics and Motor Control of Human Movement (4th ed., 2009), Table 4.1.
enum class SegmentTable { kDeLeva, kDempster };
// "de_leva"/"deleva" or "dempster"; std::invalid_argument naming the text otherwise.
SegmentTable segment_table_from_string(const std::string& text);

// One row of Winter's Table 4.1 (Dempster's data): the segment's mass as a fraction of the body's
// and its mass center's distance from the proximal end as a fraction of the segment's length.
struct DempsterRow {
  const char* name;
  const char* proximal;
  const char* distal;
  double mass;
  double mass_center;
};
// The rows used: head and neck, trunk, upper arm, forearm, hand, thigh, leg, foot (limbs count
// twice).
const std::vector<DempsterRow>& dempster_table();
// The sum of the rows' mass fractions, limbs twice: 1.000 as in Winter's table.
double dempster_mass_sum();

// Sets mass, mass_center and inertia of the bodies of `model` (model_from_bvh of `bvh` with
// the same `scale`) for a body of `body_mass` kg: each table segment found in the skeleton on
// the body `map` names for it, else the one the naming rules of doc/anthropometry.md find, the
// fractions of segments not found spread over the found ones in proportion, so that the masses
// sum to body_mass. Bodies covered by no segment stay massless; a body fixed in space while
// others move (a static ROOT) carries no trunk part. Returns the notes, one line each: the
// bodies without mass that no segment covers; the segments not found (the whole-body outputs
// are then incomplete). Throws std::invalid_argument "<map>: joint X is not in <bvh>".
// With `table` kDempster (doc/anthropometry.md "Dempster's table"): the masses and mass centers
// of Winter's Table 4.1 on the same bodies (one trunk; the head and neck's center at the head
// joint, standing for the ear canal; the foot from the ankle to the toe joint), each body's
// central inertia de Leva's scaled by the mass ratio (the table has no full set of radii).
std::vector<std::string> set_segment_parameters(const BvhFile& bvh, double scale, double body_mass,
                                                Sex sex, Model& model, const SegmentMap& map = {},
                                                SegmentTable table = SegmentTable::kDeLeva);

// The table's segments (e.g. "left hand", "lower trunk") that set_segment_parameters finds no
// body for in `bvh`'s skeleton; empty when every mass-carrying segment is there.
std::vector<std::string> missing_segments(const BvhFile& bvh, double scale,
                                          const SegmentMap& map = {});

}  // namespace mbk
