// cairo, loaded when first drawn with: the functions `gmg render` and `gmg evaluate --plot` call,
// each forwarding to the library opened with dlopen on the first call. Linking cairo itself would
// load it, and the forty shared libraries beneath it (fontconfig, freetype, pixman, X11, ...), at
// the start of every command; these definitions stand in for the library's at link time, with
// its own prototypes (cairo.h), so the compiler checks each against it. A cairo that cannot be
// loaded ends the process with a one-line error (there is nothing to draw with).
//
// To call another cairo function, add it to the list below.
#include <dlfcn.h>

#include <cairo-svg.h>
#include <cairo.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace {

void* cairo_library() {
  static void* lib = [] {
    void* l = nullptr;
    for (const char* name : {GMG_CAIRO_SONAME, "libcairo.so.2", "libcairo.so"})
      if ((l = dlopen(name, RTLD_NOW | RTLD_LOCAL)) != nullptr) break;
    if (!l) {
      const char* why = dlerror();
      std::fprintf(stderr, "gmg: error: cannot draw: the cairo library could not be loaded (%s)\n",
                   why ? why : GMG_CAIRO_SONAME);
      std::exit(1);
    }
    return l;
  }();
  return lib;
}

template <typename F>
F cairo_function(const char* name) {
  void* f = dlsym(cairo_library(), name);
  if (!f) {
    std::fprintf(stderr, "gmg: error: cannot draw: the cairo library has no %s\n", name);
    std::exit(1);
  }
  return reinterpret_cast<F>(f);
}

}  // namespace

// Each: the library's function, looked up once (a function-local static is thread-safe).
#define GMG_CAIRO_FORWARD(name, call)                             \
  static const auto f = cairo_function<decltype(&::name)>(#name); \
  return f call

extern "C" {

void cairo_arc(cairo_t* cr, double xc, double yc, double radius, double angle1, double angle2) {
  GMG_CAIRO_FORWARD(cairo_arc, (cr, xc, yc, radius, angle1, angle2));
}
void cairo_clip(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_clip, (cr)); }
void cairo_close_path(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_close_path, (cr)); }
cairo_t* cairo_create(cairo_surface_t* target) { GMG_CAIRO_FORWARD(cairo_create, (target)); }
void cairo_destroy(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_destroy, (cr)); }
void cairo_fill(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_fill, (cr)); }
void cairo_fill_preserve(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_fill_preserve, (cr)); }
cairo_surface_t* cairo_image_surface_create(cairo_format_t format, int width, int height) {
  GMG_CAIRO_FORWARD(cairo_image_surface_create, (format, width, height));
}
cairo_surface_t* cairo_image_surface_create_from_png(const char* filename) {
  GMG_CAIRO_FORWARD(cairo_image_surface_create_from_png, (filename));
}
unsigned char* cairo_image_surface_get_data(cairo_surface_t* surface) {
  GMG_CAIRO_FORWARD(cairo_image_surface_get_data, (surface));
}
int cairo_image_surface_get_height(cairo_surface_t* surface) {
  GMG_CAIRO_FORWARD(cairo_image_surface_get_height, (surface));
}
int cairo_image_surface_get_stride(cairo_surface_t* surface) {
  GMG_CAIRO_FORWARD(cairo_image_surface_get_stride, (surface));
}
int cairo_image_surface_get_width(cairo_surface_t* surface) {
  GMG_CAIRO_FORWARD(cairo_image_surface_get_width, (surface));
}
void cairo_line_to(cairo_t* cr, double x, double y) { GMG_CAIRO_FORWARD(cairo_line_to, (cr, x, y)); }
void cairo_move_to(cairo_t* cr, double x, double y) { GMG_CAIRO_FORWARD(cairo_move_to, (cr, x, y)); }
void cairo_new_path(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_new_path, (cr)); }
void cairo_new_sub_path(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_new_sub_path, (cr)); }
void cairo_paint(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_paint, (cr)); }
void cairo_paint_with_alpha(cairo_t* cr, double alpha) { GMG_CAIRO_FORWARD(cairo_paint_with_alpha, (cr, alpha)); }
void cairo_pattern_add_color_stop_rgb(cairo_pattern_t* pattern, double offset, double red, double green, double blue) {
  GMG_CAIRO_FORWARD(cairo_pattern_add_color_stop_rgb, (pattern, offset, red, green, blue));
}
cairo_pattern_t* cairo_pattern_create_linear(double x0, double y0, double x1, double y1) {
  GMG_CAIRO_FORWARD(cairo_pattern_create_linear, (x0, y0, x1, y1));
}
cairo_pattern_t* cairo_pattern_create_radial(double cx0, double cy0, double radius0, double cx1, double cy1,
                                             double radius1) {
  GMG_CAIRO_FORWARD(cairo_pattern_create_radial, (cx0, cy0, radius0, cx1, cy1, radius1));
}
void cairo_pattern_destroy(cairo_pattern_t* pattern) { GMG_CAIRO_FORWARD(cairo_pattern_destroy, (pattern)); }
void cairo_pop_group_to_source(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_pop_group_to_source, (cr)); }
void cairo_push_group(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_push_group, (cr)); }
void cairo_rectangle(cairo_t* cr, double x, double y, double width, double height) {
  GMG_CAIRO_FORWARD(cairo_rectangle, (cr, x, y, width, height));
}
void cairo_restore(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_restore, (cr)); }
void cairo_save(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_save, (cr)); }
void cairo_select_font_face(cairo_t* cr, const char* family, cairo_font_slant_t slant, cairo_font_weight_t weight) {
  GMG_CAIRO_FORWARD(cairo_select_font_face, (cr, family, slant, weight));
}
void cairo_set_font_size(cairo_t* cr, double size) { GMG_CAIRO_FORWARD(cairo_set_font_size, (cr, size)); }
void cairo_set_line_width(cairo_t* cr, double width) { GMG_CAIRO_FORWARD(cairo_set_line_width, (cr, width)); }
void cairo_set_operator(cairo_t* cr, cairo_operator_t op) { GMG_CAIRO_FORWARD(cairo_set_operator, (cr, op)); }
void cairo_set_source(cairo_t* cr, cairo_pattern_t* source) { GMG_CAIRO_FORWARD(cairo_set_source, (cr, source)); }
void cairo_set_source_rgb(cairo_t* cr, double red, double green, double blue) {
  GMG_CAIRO_FORWARD(cairo_set_source_rgb, (cr, red, green, blue));
}
void cairo_set_source_rgba(cairo_t* cr, double red, double green, double blue, double alpha) {
  GMG_CAIRO_FORWARD(cairo_set_source_rgba, (cr, red, green, blue, alpha));
}
void cairo_set_source_surface(cairo_t* cr, cairo_surface_t* surface, double x, double y) {
  GMG_CAIRO_FORWARD(cairo_set_source_surface, (cr, surface, x, y));
}
void cairo_show_text(cairo_t* cr, const char* utf8) { GMG_CAIRO_FORWARD(cairo_show_text, (cr, utf8)); }
const char* cairo_status_to_string(cairo_status_t status) { GMG_CAIRO_FORWARD(cairo_status_to_string, (status)); }
void cairo_stroke(cairo_t* cr) { GMG_CAIRO_FORWARD(cairo_stroke, (cr)); }
void cairo_surface_destroy(cairo_surface_t* surface) { GMG_CAIRO_FORWARD(cairo_surface_destroy, (surface)); }
void cairo_surface_finish(cairo_surface_t* surface) { GMG_CAIRO_FORWARD(cairo_surface_finish, (surface)); }
void cairo_surface_flush(cairo_surface_t* surface) { GMG_CAIRO_FORWARD(cairo_surface_flush, (surface)); }
cairo_status_t cairo_surface_status(cairo_surface_t* surface) { GMG_CAIRO_FORWARD(cairo_surface_status, (surface)); }
cairo_status_t cairo_surface_write_to_png_stream(cairo_surface_t* surface, cairo_write_func_t write_func,
                                                 void* closure) {
  GMG_CAIRO_FORWARD(cairo_surface_write_to_png_stream, (surface, write_func, closure));
}
cairo_surface_t* cairo_svg_surface_create_for_stream(cairo_write_func_t write_func, void* closure,
                                                     double width_in_points, double height_in_points) {
  GMG_CAIRO_FORWARD(cairo_svg_surface_create_for_stream, (write_func, closure, width_in_points, height_in_points));
}
void cairo_text_extents(cairo_t* cr, const char* utf8, cairo_text_extents_t* extents) {
  GMG_CAIRO_FORWARD(cairo_text_extents, (cr, utf8, extents));
}
}  // extern "C"
