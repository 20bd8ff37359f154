// A depth buffer's window depth (0 to 1) as the view depth (metres along the view axis) of a
// perspective projection with these near and far planes: the one formula of every program that
// reads the frame's depth.
float view_depth(float window, float near_plane, float far_plane)
{
    float z = window * 2.0 - 1.0;
    return 2.0 * near_plane * far_plane / (far_plane + near_plane - z * (far_plane - near_plane));
}

// The same, or 3e38 for the sky (window depth 1): as far as any volume goes.
float view_depth_or_sky(float window, float near_plane, float far_plane)
{
    return window >= 1.0 ? 3e38 : view_depth(window, near_plane, far_plane);
}
