/* vec.c - 3-vectors for the public API (math stage; any thread). */
#include "softrast.h"

#include <math.h>

sr_vec3 sr_vec3_make(float x, float y, float z) { return (sr_vec3){ x, y, z }; }
sr_vec3 sr_vec3_add(sr_vec3 a, sr_vec3 b) { return (sr_vec3){ a.x + b.x, a.y + b.y, a.z + b.z }; }
sr_vec3 sr_vec3_sub(sr_vec3 a, sr_vec3 b) { return (sr_vec3){ a.x - b.x, a.y - b.y, a.z - b.z }; }
sr_vec3 sr_vec3_scale(sr_vec3 a, float s) { return (sr_vec3){ a.x * s, a.y * s, a.z * s }; }
float sr_vec3_dot(sr_vec3 a, sr_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

sr_vec3 sr_vec3_cross(sr_vec3 a, sr_vec3 b)
{
    return (sr_vec3){ a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}

float sr_vec3_length(sr_vec3 a) { return sqrtf(sr_vec3_dot(a, a)); }

sr_vec3 sr_vec3_normalize(sr_vec3 a)
{
    float len = sr_vec3_length(a);
    return len > 0.0f ? sr_vec3_scale(a, 1.0f / len) : a;
}
