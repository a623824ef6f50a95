// libFuzzer harness: the picture of the rviz display and the node's markers (mb_kinematics/viz/)
// on bodies decoded from the input: positions and vectors from 1e-3 to 1e30 m (NaN and inf
// among them), names up to 100,000 characters (with "__" or not), a user's filter or the
// default, a random max_bodies. Every glyph a single-precision renderer gets is finite (arrows:
// a unit direction and a positive length), none is drawn beyond kMaxGlyphDistance, and at most
// max_bodies bodies are drawn.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "mb_kinematics/viz/glyphs.h"
#include "mb_kinematics/viz/local_glyphs.h"
#include "test/fuzz/fuzz_support.h"

namespace {

class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool empty() const { return at_ >= size_; }
  uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  // A coordinate: 0, NaN, inf, or +-(1 + byte / 256) * 10^e, e from -3 to 30.
  double number() {
    const uint8_t kind = byte();
    if (kind == 255) return std::numeric_limits<double>::quiet_NaN();
    if (kind == 254) return -std::numeric_limits<double>::infinity();
    if (kind < 8) return 0;
    const double mantissa = (1 + byte() / 256.0) * (kind & 1 ? -1 : 1);
    return mantissa * std::pow(10.0, static_cast<int>(kind % 34) - 3);
  }
  mbk::Vec3<double> vec() {
    const double x = number(), y = number(), z = number();
    return {x, y, z};
  }
  std::string name() {
    const uint8_t length = byte(), c = byte();
    const size_t n = length < 240 ? length : (length - 239) * 6000u;  // up to 96,000
    std::string s(n, static_cast<char>('a' + c % 26));
    if (c & 0x80) s += "__alpha";
    return s + std::to_string(at_);
  }

 private:
  const uint8_t* data_;
  size_t size_, at_ = 0;
};

void check(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style) {
  if (glyphs.mass_centers.size() > style.max_bodies) mbk_fuzz::finding("more than max_bodies");
  const mbk::Vec3<double> anchor = mbk::glyph_anchor(glyphs);
  if (!anchor.allFinite()) mbk_fuzz::finding("anchor not finite");
  for (const mbk::GlyphArrow& a : glyphs.arrows) {
    if (a.start.lpNorm<Eigen::Infinity>() > mbk::kMaxGlyphDistance)
      mbk_fuzz::finding("an arrow beyond kMaxGlyphDistance");
    const auto local = mbk::local_arrow(a.start, a.vector, anchor);
    if (!local || !local->start.allFinite() || !(local->length > 0) ||
        !(std::abs(local->direction.norm() - 1) < 1e-5))
      mbk_fuzz::finding("an arrow a float renderer cannot draw");
  }
  for (const mbk::GlyphArc& arc : glyphs.arcs)
    for (const mbk::Vec3<double>& p : arc.points)
      if (!mbk::local_point(p, anchor).allFinite()) mbk_fuzz::finding("an arc point not finite");
  for (const mbk::Vec3<double>& g : glyphs.mass_centers)
    if (!mbk::local_point(g, anchor).allFinite()) mbk_fuzz::finding("a sphere not finite");
  for (const auto& line : glyphs.skeleton)
    if (!mbk::local_point(line.first, anchor).allFinite() ||
        !mbk::local_point(line.second, anchor).allFinite())
      mbk_fuzz::finding("a skeleton line not finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Bytes in(data, size);
  mbk::GlyphStyle style;
  const uint8_t options = in.byte();
  style.skeleton = options & 1;
  if (options & 2) style.filter = mbk::BodyFilter("^[a-m]", options & 4 ? "z$" : "");
  style.max_bodies = in.byte() % 64;
  std::vector<mbk::GlyphBody> bodies;
  while (!in.empty() && bodies.size() < 256) {
    mbk::GlyphBody b;
    b.name = in.name();
    b.index = in.byte();
    b.lower = in.byte();
    b.origin = in.vec();
    b.mass_center = b.origin + in.vec();
    for (mbk::Vec3<double>& v : b.vectors) v = in.vec();
    bodies.push_back(b);
  }
  for (int q = 0; q < mbk::GlyphQuantity::kCount; ++q)
    if (!std::isfinite(mbk::max_norm(bodies, style, q))) mbk_fuzz::finding("max_norm not finite");
  check(mbk::make_glyphs(bodies, style), style);
  return 0;
}
