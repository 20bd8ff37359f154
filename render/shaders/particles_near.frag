#version 450 core
// The particles' near field (ParticlesPass, particles alone): the Medium itself, marched from the
// eye to u_reach along each pixel's ray (or to the terrain, nearer), lit by the model every fog
// renderer shares (froxel_light.glsl's medium_light: the sun through the sun volume's tau_sun, in
// the terrain's shadow, the baked light where the Medium's model is `baked`), hazed by the air
// as the billboards are. The billboards draw their balls from u_reach on: within it a few balls
// a hundred metres and more across stand for all the fog the eye sees, each a blot over a fifth
// of the frame (from inside the descent's blanket, 85 % of the optical depth of the frame's
// lowest rows came from balls within 1.5 radii of the eye, 20 % more than the Medium's there).
// Premultiplied (radiance, 1 - T), laid over the frame after every billboard: it lies in front
// of them all.
in vec2 v_ndc;
uniform sampler2D u_depth;  // the terrain's depth, full resolution
uniform vec2 u_depth_scale; // its pixels per pixel of this target
uniform float u_near;
uniform float u_far;
uniform float u_reach;      // metres along each ray
uniform int u_steps;
out vec4 o_color;

void main()
{
    vec2 uv = v_ndc * 0.5 + 0.5;
    vec3 ray = fx_ray(uv);
    float stretch = length(ray);
    vec3 unit = ray / stretch;
    ivec2 size = textureSize(u_depth, 0);
    ivec2 pixel = clamp(ivec2(gl_FragCoord.xy * u_depth_scale), ivec2(0), size - 1);
    float scene = view_depth(texelFetch(u_depth, pixel, 0).r, u_near, u_far) * stretch;
    float end = min(u_reach, scene);
    // Four stretches of u_steps / 4 steps each: the light's two parts taken at each stretch's
    // ends (froxel_light.glsl's medium_light_parts_at: the light in the terrain's shadow and the
    // sun's share, through the air), linear between them, the terrain's visibility of the sun
    // at each step (the whole light at every step cost three times the whole march). Each step's optical depth from the density at two
    // points half a step apart: at the same places in every step of a pixel, different ones in
    // each pixel (interleaved gradient noise, [Jimenez14]). The detail noise shifts with the
    // height in the column (Medium::detail_factor: two tiles over a column's depth), so the
    // density changes within a metre of height: steps at the same fractions of each ray drew
    // bands along the ground's contours, one point a step a crosshatch at this target's scale.
    // One light a pass of the outer loop: llvmpipe runs a branch's code whether any lane takes
    // it or not, so a light taken at every eighth step behind a branch would cost every step.
    const int stretches = 4;
    int per = max(u_steps / stretches, 1);
    float dt = end / float(stretches * per);
    float offset = fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    vec3 radiance = vec3(0.0);
    float through = 1.0;
    // (The first a millimetre ahead of the eye: the parts take the view's direction from p - eye.)
    vec4 j0 = medium_light_parts_at(u_fx_eye + unit * 1e-3, u_fx_eye, 0.5), j1 = j0;
    for (int s = 0; s < stretches; ++s) {
        j0 = j1;
        j1 = medium_light_parts_at(u_fx_eye + unit * (end * float(s + 1) / float(stretches)), u_fx_eye, 0.5);
        for (int i = 0; i < per; ++i) {
            float u = (float(i) + 0.5 * offset + 0.25) / float(per);  // the two points' middle
            float at = float(s * per + i) + 0.5 * offset;  // the first point, in steps
            vec3 a = u_fx_eye + unit * (at * dt), b = u_fx_eye + unit * ((at + 0.5) * dt);
            float sigma = 0.5 * (medium_sigma(a) + medium_sigma(b));
            float step_through = exp(-sigma * dt);
            // The terrain's visibility of the sun at the step's own point: the shade a canyon's
            // wall casts into its fog has edges metres wide, which a light drawn linear over a
            // stretch smeared (the canyon from inside its fog 2.86 % off the reference so, 1.67 %
            // with the whole light at every step).
            vec3 j = medium_light_from_parts(mix(j0, j1, u), medium_visibility_at(0.5 * (a + b)));
            radiance += through * (1.0 - step_through) * j;
            through *= step_through;
        }
    }
    if (!(through < 1.0 - 1e-6))
        discard;
    o_color = vec4(radiance, 1.0 - through);
}
