// buildSegmentXfb, vertex stage: one point per source vertex, carrying its index to the geometry
// stage, which builds the segment (build_segment_xfb.geom).
#version 450

layout(location = 0) flat out uint sourceIndex;

void main() {
    sourceIndex = uint(gl_VertexIndex);
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
