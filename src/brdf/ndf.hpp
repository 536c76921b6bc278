#pragma once
// Normal distribution functions D(h), each normalized so that int D(h) (n.h) dw_h = 1 (checked by
// tests/brdf/test_ndf.cpp): the D_* terms and gaussianNormalization (ndf.cpp) are in brdf/terms.hpp.

#include "hilite/brdf/terms.hpp"
