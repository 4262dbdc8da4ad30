/* SPDX-License-Identifier: MIT */
/* fbrl_urdf.c - fbrl-urdf: an arm model of the library (fbrl/arm.h) as URDF, so outside
 * tools (ROS's check_urdf, RViz, urdf viewers) draw the arm fbrl drives.
 *
 *   fbrl-urdf [MODEL]        (a255, the default, or a465)
 *
 * The chain is the library's own kinematics written as URDF joints: each joint's axis and
 * the fixed offsets between them come from the model's row (base height, upper arm, forearm,
 * flange), its limits and speeds likewise; link tool0 is the flange, where fbrl_arm_fk puts
 * the tool point with no tool. Lengths are metres and angles radians, as URDF wants them.
 * Effort is not known for these arms: it is written as 0. */
#include <stdio.h>
#include <string.h>

#include "fbrl/arm.h"
#include "fbrl/version.h"

enum { EXIT_USAGE = 2 };

#define PI        3.14159265358979323846
#define M_PER_IN  0.0254
#define RAD(d)    ((d) * (PI / 180.0))
#define NAMES_CAP 64

typedef struct joint_row {
    const char *name, *parent, *child;
    double xyz[3];  /* in the parent link's frame, inches */
    double rpy[3];  /* radians */
    double axis[3]; /* in the joint's frame */
} joint_row;

/* A255 (5R): the links point along x; the shoulder, elbow and wrist pitch turn about -y, so a
 * positive angle lifts the next link (fbrl/arm.h: the upper arm above horizontal). */
static unsigned chain5(const fbrl_arm *m, joint_row *j)
{
    const joint_row rows[] = {
        {"waist", "base_link", "waist_link", {0, 0, 0}, {0, 0, 0}, {0, 0, 1}},
        {"shoulder", "waist_link", "upper_arm", {0, 0, m->base_h}, {0, 0, 0}, {0, -1, 0}},
        {"elbow", "upper_arm", "forearm", {m->upper, 0, 0}, {0, 0, 0}, {0, -1, 0}},
        {"wrist_pitch", "forearm", "wrist", {m->fore, 0, 0}, {0, 0, 0}, {0, -1, 0}},
        {"tool_roll", "wrist", "hand", {0, 0, 0}, {0, 0, 0}, {1, 0, 0}},
    };
    memcpy(j, rows, sizeof rows);
    return 5;
}

/* A465 (6R): the upper arm and the forearm point along z (the shoulder from vertical, forward
 * positive, about y); at the wrist centre the frame turns so x runs along the forearm, then
 * the spherical wrist Rx(q4) Ry(q5) Rx(q6) (src/arm.c, wrist_rot). */
static unsigned chain6(const fbrl_arm *m, joint_row *j)
{
    const joint_row rows[] = {
        {"waist", "base_link", "waist_link", {0, 0, 0}, {0, 0, 0}, {0, 0, 1}},
        {"shoulder", "waist_link", "upper_arm", {0, 0, m->base_h}, {0, 0, 0}, {0, 1, 0}},
        {"elbow", "upper_arm", "forearm", {0, 0, m->upper}, {0, 0, 0}, {0, 1, 0}},
        {"forearm_roll", "forearm", "wrist_roll", {0, 0, m->fore}, {0, -PI / 2, 0}, {1, 0, 0}},
        {"wrist_bend", "wrist_roll", "wrist", {0, 0, 0}, {0, 0, 0}, {0, 1, 0}},
        {"tool_roll", "wrist", "hand", {0, 0, 0}, {0, 0, 0}, {1, 0, 0}},
    };
    memcpy(j, rows, sizeof rows);
    return 6;
}

/* A link drawn as the arm's body: a cylinder of radius r from the link's origin length
 * inches along x (5R) or z (6R). */
static void link(const char *name, double len, double r, int along_x)
{
    printf("  <link name=\"%s\">\n", name);
    if (len > 0 && r > 0) {
        printf("    <visual>\n      <origin xyz=\"%.9g 0 %.9g\" rpy=\"0 %.9g 0\"/>\n", along_x ? len / 2 * M_PER_IN : 0.0,
               along_x ? 0.0 : len / 2 * M_PER_IN, along_x ? PI / 2 : 0.0);
        printf("      <geometry><cylinder radius=\"%.9g\" length=\"%.9g\"/></geometry>\n    </visual>\n",
               r * M_PER_IN, len * M_PER_IN);
    }
    printf("  </link>\n");
}

static void usage(FILE *f)
{
    char names[NAMES_CAP];
    fbrl_arm_names(names, sizeof names, '|');
    fprintf(f, "usage: fbrl-urdf [%s]\nPrint the arm model (default a255) as URDF.\n", names);
}

int main(int argc, char **argv)
{
    joint_row j[FBRL_ARM_AXES_MAX];
    const char *name = "a255";
    if (argc > 2) {
        usage(stderr);
        return EXIT_USAGE;
    }
    if (argc == 2 && (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help"))) {
        usage(stdout);
        return 0;
    }
    if (argc == 2 && (!strcmp(argv[1], "-V") || !strcmp(argv[1], "--version"))) {
        printf("fbrl-urdf (libfbrl) %s\n", FBRL_VERSION_STRING);
        return 0;
    }
    if (argc == 2)
        name = argv[1];
    const fbrl_arm *m = fbrl_arm_find(name);
    if (!m) {
        fprintf(stderr, "fbrl-urdf: no arm model %s\n", name);
        usage(stderr);
        return EXIT_USAGE;
    }
    int five = m->form == FBRL_ARM_5R;
    unsigned n = five ? chain5(m, j) : chain6(m, j);
    char lower[16];
    size_t k;
    for (k = 0; m->name[k] && k + 1 < sizeof lower; k++)
        lower[k] = (char)(m->name[k] >= 'A' && m->name[k] <= 'Z' ? m->name[k] + 32 : m->name[k]);
    lower[k] = '\0';
    printf("<?xml version=\"1.0\"?>\n<!-- CRS %s as libfbrl %s models it (fbrl-urdf %s): lengths in metres, "
           "angles in radians; tool0 is the flange. -->\n<robot name=\"crs_%s\">\n",
           m->name, FBRL_VERSION_STRING, lower, lower);
    link("base_link", m->base_h, m->r_upper, 0);
    link("waist_link", 0, 0, 0);
    link("upper_arm", m->upper, m->r_upper, five);
    link("forearm", m->fore, m->r_fore, five);
    if (!five)
        link("wrist_roll", 0, 0, 0);
    link("wrist", 0, 0, 0);
    link("hand", m->flange, m->r_fore / 2, 1);
    link("tool0", 0, 0, 0);
    for (unsigned i = 0; i < n; i++) {
        printf("  <joint name=\"%s\" type=\"revolute\">\n    <parent link=\"%s\"/>\n    <child link=\"%s\"/>\n",
               j[i].name, j[i].parent, j[i].child);
        printf("    <origin xyz=\"%.9g %.9g %.9g\" rpy=\"%.9g %.9g %.9g\"/>\n", j[i].xyz[0] * M_PER_IN,
               j[i].xyz[1] * M_PER_IN, j[i].xyz[2] * M_PER_IN, j[i].rpy[0], j[i].rpy[1], j[i].rpy[2]);
        printf("    <axis xyz=\"%g %g %g\"/>\n", j[i].axis[0], j[i].axis[1], j[i].axis[2]);
        printf("    <limit lower=\"%.9g\" upper=\"%.9g\" effort=\"0\" velocity=\"%.9g\"/>\n  </joint>\n",
               RAD(m->min[i]), RAD(m->max[i]), RAD(m->speed[i]));
    }
    printf("  <joint name=\"flange\" type=\"fixed\">\n    <parent link=\"hand\"/>\n    <child link=\"tool0\"/>\n"
           "    <origin xyz=\"%.9g 0 0\" rpy=\"0 0 0\"/>\n  </joint>\n</robot>\n",
           m->flange * M_PER_IN);
    return ferror(stdout) ? 1 : 0;
}
