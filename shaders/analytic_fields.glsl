// SPDX-License-Identifier: BSD-3-Clause
// The analytic fields of lic/analytic_fields.cpp (the oracle, in double precision) in float, for
// the shaders that make them on the device. The includer declares nothing: the field is this
// file's specialization constant.
#ifndef LIC3D_ANALYTIC_FIELDS_GLSL
#define LIC3D_ANALYTIC_FIELDS_GLSL

// The AnalyticField.
layout(constant_id = kAnalyticConstField) const uint FIELD = kAnalyticDefaultField;

// Crawfis' tornado, as lic/analytic_fields.cpp writes it.
vec3 tornado(vec3 p, float time) {
  float x = p.x, y = p.y, z = p.z;
  float xc = 0.5 + 0.1 * sin(0.04 * time + 10.0 * z);
  float yc = 0.5 + 0.1 * cos(0.03 * time + 3.0 * z);
  float r = 0.1 + 0.4 * z * z + 0.1 * z * sin(8.0 * z);
  float r2 = 0.2 + 0.1 * z;
  float temp = sqrt((y - yc) * (y - yc) + (x - xc) * (x - xc));
  float scale = abs(r - temp);
  scale = scale > r2 ? 0.8 - scale : 1.0;
  float z0 = max(0.1 * (0.1 - temp * z), 0.0);
  temp = sqrt(temp * temp + z0 * z0);
  scale = (r + r2 - temp) * scale / (temp + 1e-11);
  scale = scale / (1.0 + z);
  return vec3(scale * (y - yc) + 0.1 * (x - xc), scale * -(x - xc) + 0.1 * (y - yc), scale * z0);
}

vec3 evaluate(vec3 p, float time) {
  float x = p.x, y = p.y, z = p.z;
  if (FIELD == 0) return tornado(p, time);
  if (FIELD == 1)  // corner (thesis 4.5)
    return vec3(-3.0 + 6.0 * x - 4.0 * x * (y + 1.0) - 4.0 * z,
                12.0 * x - 4.0 * x * x - 12.0 * z + 4.0 * z * z,
                3.0 + 4.0 * x - 4.0 * x * (y + 1.0) - 6.0 * z + 4.0 * (y + 1.0) * z);
  if (FIELD == 2)  // solenoidal (thesis 6.2)
    return vec3(y * z * (y * y + z * z), x * z * (x * x + z * z), x * y * (x * x + y * y));
  if (FIELD == 3) return vec3(-y, x, 0.2);  // vortex
  // ABC flow
  const float a = sqrt(3.0), b = sqrt(2.0), c = 1.0;
  return vec3(a * sin(z) + c * cos(y), b * sin(x) + a * cos(z), c * sin(y) + b * cos(x));
}

#endif
