#include "quadrix/draw/page.h"

namespace quadrix::draw {

Page SingleViewPage(const Drawing& d, const std::string& title) {
    Page p;
    p.width = d.width;
    p.height = d.height;
    p.unit = "px";
    p.strokes = d.strokes;
    p.title = title;
    return p;
}

}  // namespace quadrix::draw
