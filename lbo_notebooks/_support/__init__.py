"""Private tools every layer uses: warnings, argument checks, optional open3d, progress bars."""
