// quadrix-cairo.so: plays a CairoJob (src/quadrix/draw/cairo_module.h) on a Cairo surface.
#include "quadrix/draw/cairo_module.h"

#include <cairo-pdf.h>
#include <cairo-ps.h>
#include <cairo.h>

namespace quadrix::draw {

namespace {

cairo_status_t Append(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

void Play(cairo_t* cr, const CairoJob& job) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_tolerance(cr, 0.001);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    using Op = CairoCommand::Op;
    for (const CairoCommand& c : job.commands) {
        const double* v = c.v;
        switch (c.op) {
            case Op::kNewPath:
                cairo_new_path(cr);
                break;
            case Op::kMoveTo:
                cairo_move_to(cr, v[0], v[1]);
                break;
            case Op::kLineTo:
                cairo_line_to(cr, v[0], v[1]);
                break;
            case Op::kCurveTo:
                cairo_curve_to(cr, v[0], v[1], v[2], v[3], v[4], v[5]);
                break;
            case Op::kEllipseArc: {
                cairo_save(cr);
                cairo_matrix_t m;
                cairo_matrix_init(&m, v[0], v[1], v[2], v[3], v[4], v[5]);
                cairo_transform(cr, &m);
                cairo_arc(cr, 0, 0, 1, v[6], v[7]);
                cairo_restore(cr);  // the stroke's pen stays round
                break;
            }
            case Op::kStroke:
                cairo_stroke(cr);
                break;
            case Op::kLineWidth:
                cairo_set_line_width(cr, v[0]);
                break;
            case Op::kDash:
                cairo_set_dash(cr, v, 2, 0);
                break;
            case Op::kSolid:
                cairo_set_dash(cr, nullptr, 0, 0);
                break;
            case Op::kGray:
                cairo_set_source_rgb(cr, v[0], v[0], v[0]);
                break;
            case Op::kText:
                if (c.index < job.texts.size()) {
                    cairo_set_font_size(cr, v[2]);
                    cairo_move_to(cr, v[0], v[1]);
                    cairo_show_text(cr, job.texts[c.index].c_str());
                }
                break;
        }
    }
}

bool Fail(std::string* error, cairo_status_t status) {
    *error = std::string("Cairo: ") + cairo_status_to_string(status);
    return false;
}

bool Render(const CairoJob& job, std::string* bytes, std::string* error) {
    bytes->clear();
    if (job.format == CairoJob::Format::kPng) {
        cairo_surface_t* img =
            cairo_image_surface_create(CAIRO_FORMAT_RGB24, job.pixelWidth, job.pixelHeight);
        cairo_t* cr = cairo_create(img);
        cairo_scale(cr, job.pixelsPerUnit, job.pixelsPerUnit);
        Play(cr, job);
        const cairo_status_t drawn = cairo_status(cr);
        cairo_destroy(cr);
        const cairo_status_t written = drawn == CAIRO_STATUS_SUCCESS
                                           ? cairo_surface_write_to_png_stream(img, Append, bytes)
                                           : drawn;
        cairo_surface_destroy(img);
        return written == CAIRO_STATUS_SUCCESS || Fail(error, written);
    }
    cairo_surface_t* surface =
        job.format == CairoJob::Format::kPdf
            ? cairo_pdf_surface_create_for_stream(Append, bytes, job.widthPt, job.heightPt)
            : cairo_ps_surface_create_for_stream(Append, bytes, job.widthPt, job.heightPt);
    if (const cairo_status_t s = cairo_surface_status(surface); s != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(surface);
        return Fail(error, s);
    }
    if (job.format == CairoJob::Format::kEps) cairo_ps_surface_set_eps(surface, 1);
    if (job.format == CairoJob::Format::kPdf && !job.title.empty())
        cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, job.title.c_str());
    cairo_t* cr = cairo_create(surface);
    cairo_scale(cr, job.pointsPerUnit, job.pointsPerUnit);
    Play(cr, job);
    cairo_show_page(cr);
    const cairo_status_t status = cairo_status(cr);
    cairo_destroy(cr);
    cairo_surface_finish(surface);
    const cairo_status_t finished = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    if (status != CAIRO_STATUS_SUCCESS) return Fail(error, status);
    return finished == CAIRO_STATUS_SUCCESS || Fail(error, finished);
}

}  // namespace

}  // namespace quadrix::draw

extern "C" __attribute__((visibility("default"))) const quadrix::draw::CairoModule*
quadrix_cairo_module() {
    static const quadrix::draw::CairoModule table{quadrix::draw::kCairoModuleAbi,
                                                  &quadrix::draw::Render};
    return &table;
}
