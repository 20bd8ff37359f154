// A depth buffer's window depth (0 to 1) as the view depth (metres along the view axis) of a
// perspective projection with these near and far planes: the one formula of every program that
// reads the frame's depth.
float view_depth(float window, float near_plane, float far_plane)
{
    float z = window * 2.0 - 1.0;
    return 2.0 * near_plane * far_plane / (far_plane + near_plane - z * (far_plane - near_plane));
}
