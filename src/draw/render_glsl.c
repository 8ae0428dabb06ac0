/* render_glsl.c - the GLSL programs of render.c, as text (no GL headers here) */
#include "draw/render_glsl.h"


/* lit share at a floor point: one bilinear tap of the blurred shadow map */
#define SHADOW_GLSL                                                                     \
	"uniform sampler2D smap;\n"                                                     \
	"uniform vec3 sbox;\n"                                                          \
	"float lit(vec2 xz) {\n"                                                        \
	"  vec2 t = (xz - sbox.xy) * sbox.z + 0.5;\n"                                   \
	"  if (sbox.z <= 0.0 || any(lessThan(t, vec2(0.0))) || any(greaterThan(t, vec2(1.0))))\n" \
	"    return 1.0;\n"                                                             \
	"  return 1.0 - 0.5 * (1.0 - texture2D(smap, t).r);\n"                          \
	"}\n"

const char render_glsl_lit_vs[] =
	"#version 120\n"
	"varying vec3 n_eye, p_eye, w;\n"
	"varying vec4 col;\n"
	"void main() {\n"
	"  w = gl_Vertex.xyz;\n"
	"  vec4 pe = gl_ModelViewMatrix * gl_Vertex;\n"
	"  p_eye = pe.xyz;\n"
	"  n_eye = gl_NormalMatrix * gl_Normal;\n"
	"  col = gl_Color;\n"
	"  gl_Position = gl_ProjectionMatrix * pe;\n"
	"}\n";

/* Blinn-Phong with a key and a fill light over a sky / ground ambient term */
const char render_glsl_lit_fs[] =
	"#version 120\n"
	"varying vec3 n_eye, p_eye, w;\n"
	"varying vec4 col;\n"
	"uniform vec3 key, fill, up;\n"
	SHADOW_GLSL
	"void main() {\n"
	"  vec3 n = normalize(n_eye);\n"
	"  vec3 v = normalize(-p_eye);\n"
	"  if (!gl_FrontFacing) n = -n;\n"
	"  float kd = max(dot(n, key), 0.0);\n"
	/* floor-level faces (a vehicle's floor pan) take the shadows too */
	"  if (w.y < 0.003 && dot(n, up) > 0.9) kd *= lit(w.xz);\n"
	"  float fd = max(dot(n, fill), 0.0);\n"
	"  float hemi = 0.5 + 0.5 * dot(n, up);\n"
	"  vec3 amb = mix(vec3(0.22, 0.21, 0.20), vec3(0.42, 0.45, 0.50), hemi);\n"
	"  float sp = kd > 0.0 ? pow(max(dot(n, normalize(key + v)), 0.0), 32.0) : 0.0;\n"
	"  float rim = pow(1.0 - max(dot(n, v), 0.0), 3.0);\n"
	"  vec3 c = col.rgb * (amb + kd * vec3(0.78, 0.76, 0.72) + fd * vec3(0.22, 0.25, 0.30))\n"
	"         + 0.18 * sp + 0.08 * rim;\n"
	"  gl_FragColor = vec4(c, col.a);\n"
	"}\n";

const char render_glsl_color_vs[] =
	"#version 120\n"
	"varying vec4 col;\n"
	"void main() {\n"
	"  col = gl_Color;\n"
	"  gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;\n"
	"}\n";

const char render_glsl_color_fs[] =
	"#version 120\n"
	"varying vec4 col;\n"
	"uniform vec4 tint;\n"
	"void main() { gl_FragColor = col * tint; }\n";

/* the floor: grid lines antialiased by their screen-space width, fading with distance */
const char render_glsl_floor_vs[] =
	"#version 120\n"
	"varying vec3 w, pe;\n"
	"void main() {\n"
	"  w = gl_Vertex.xyz;\n"
	"  pe = (gl_ModelViewMatrix * gl_Vertex).xyz;\n"
	"  gl_Position = gl_ProjectionMatrix * vec4(pe, 1.0);\n"
	"}\n";

const char render_glsl_floor_fs[] =
	"#version 120\n"
	"varying vec3 w, pe;\n"
	"uniform vec3 rgb, far_rgb;\n"
	"uniform float grid;\n"
	"uniform vec2 fade;\n"
	SHADOW_GLSL

	"float lines(vec2 g, float px) {\n"
	"  vec2 d = abs(fract(g - 0.5) - 0.5) / (fwidth(g) * px);\n"
	"  return 1.0 - min(min(d.x, d.y), 1.0);\n"
	"}\n"
	"void main() {\n"
	"  vec2 g = w.xz / grid;\n"
	"  float minor = lines(g, 1.0), major = lines(g / 2.0, 1.6);\n"
	"  vec3 c = rgb * (1.0 - 0.16 * minor) * (1.0 - 0.22 * major) * (0.35 + 0.65 * lit(w.xz));\n"
	"  float f = smoothstep(fade.x, fade.y, length(pe));\n"
	"  gl_FragColor = vec4(mix(c, far_rgb, f), 1.0);\n"
	"}\n";

/* a 3 x 3 tent of bilinear taps over the shadow map, drawn once into its blurred copy */
const char render_glsl_blur_vs[] =
	"#version 120\n"
	"varying vec2 uv;\n"
	"void main() {\n"
	"  uv = gl_Vertex.xy * 0.5 + 0.5;\n"
	"  gl_Position = vec4(gl_Vertex.xy, 0.0, 1.0);\n"
	"}\n";

const char render_glsl_blur_fs[] =
	"#version 120\n"
	"varying vec2 uv;\n"
	"uniform sampler2D src;\n"
	"void main() {\n"
	"  float d = 1.0 / 128.0, s = 0.0;\n"
	"  for (int i = -1; i <= 1; i++)\n"
	"    for (int j = -1; j <= 1; j++)\n"
	"      s += texture2D(src, uv + vec2(float(i), float(j)) * d * 1.5).r;\n"
	"  gl_FragColor = vec4(vec3(s / 9.0), 1.0);\n"
	"}\n";

const char render_glsl_text_vs[] =
	"#version 120\n"
	"varying vec4 col;\n"
	"varying vec2 uv;\n"
	"void main() {\n"
	"  col = gl_Color;\n"
	"  uv = gl_MultiTexCoord0.xy;\n"
	"  gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;\n"
	"}\n";

const char render_glsl_text_fs[] =
	"#version 120\n"
	"varying vec4 col;\n"
	"varying vec2 uv;\n"
	"uniform sampler2D atlas;\n"
	"void main() { gl_FragColor = vec4(col.rgb, col.a * texture2D(atlas, uv).a); }\n";

