// Quad precision (113-bit significand, about 34 digits) for reference builds of the core:
// the same templated algorithms instantiated with boost::multiprecision::float128.
#pragma once

#include <boost/multiprecision/eigen.hpp>
#include <boost/multiprecision/float128.hpp>

namespace mbk {

using Quad = boost::multiprecision::float128;

}  // namespace mbk
