/* render_glsl.h - the GLSL sources render.c compiles */
#ifndef POSTURE_RENDER_GLSL_H
#define POSTURE_RENDER_GLSL_H

extern const char render_glsl_lit_vs[];
extern const char render_glsl_lit_fs[];
extern const char render_glsl_color_vs[];
extern const char render_glsl_color_fs[];
extern const char render_glsl_floor_vs[];
extern const char render_glsl_floor_fs[];
extern const char render_glsl_blur_vs[];
extern const char render_glsl_blur_fs[];
extern const char render_glsl_text_vs[];
extern const char render_glsl_text_fs[];

#endif
