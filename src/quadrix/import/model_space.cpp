#include "quadrix/import/model_space.h"

namespace quadrix::import {

Mat4 QuadrixFromZUp() {
    Mat4 m = Mat4::Zero();
    m.m[0][0] = 1;
    m.m[1][2] = 1;
    m.m[2][1] = 1;
    m.m[3][3] = 1;
    return m;
}

}  // namespace quadrix::import
