/* gikiosk compare REFERENCE TEST [--json] [--exposure X] [--mask MASK]: error metrics of a test image
 * against a reference (definitions in metrics/metrics.h), as aligned text or one JSON object; with a
 * mask (e.g. the caustic mask beside a caustic reference), also over the pixels inside and outside it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/commands.h"
#include "metrics/metrics.h"

static void usage(FILE *f)
{
    fputs("usage: gikiosk compare REFERENCE TEST [--json] [--exposure X] [--mask MASK]\n"
          "\n"
          "Error metrics of TEST against REFERENCE (any format OpenImageIO reads; linear EXR expected).\n"
          "Both images must have the same size and channel count.\n"
          "\n"
          "  --json        print one JSON object instead of aligned text\n"
          "  --exposure X  scale factor applied before the tonemap for psnr and ssim\n"
          "                (default 0.18 / mean luminance of REFERENCE, 1 when that is 0)\n"
          "  --mask MASK   an image of the same size (e.g. tests/references/SCENE-caustics-mask.png):\n"
          "                also report every metric over the pixels inside it (a colour\n"
          "                channel >= 0.5) and outside it; the exposure stays the whole image's\n"
          "\n"
          "metrics (colour channels: RGB, or grey for 1-2 channel images; alpha ignored):\n"
          "  rel_rmse    sqrt(mean (t-r)^2) / mean r          linear\n"
          "  rel_mse     mean (t-r)^2 / (r^2 + 0.01)          linear\n"
          "  rmse        sqrt(mean (t-r)^2)                   linear\n"
          "  psnr        dB, peak 1, on tonemapped images; identical: inf (999 in JSON)\n"
          "  ssim        on tonemapped luminance, Gaussian 11x11 window, sigma 1.5\n"
          "  mean_ratio  mean t / mean r (energy ratio)\n"
          "  max_error   largest |t - r|, at max_error_at [x, y] (x from left, y from top)\n"
          "In JSON, other non-finite values (a NaN pixel, a ratio over a zero mean) are null.\n"
          "\n"
          "Exit: 0 metrics printed; 1 the test image holds NaN/inf values (counted in `nonfinite`, the\n"
          "metrics are printed but mean nothing); 2 bad usage or a bad file (missing, not a regular file,\n"
          "over 1 GiB, unreadable, sizes differ, NaN/inf in the reference).\n",
          f);
}

/* JSON has no inf/NaN. psnr is capped at 999 dB (identical images; real differences stay far
 * below: one 8-bit step everywhere is 48 dB); anything else non-finite prints as null. */
static void json_number(const char *key, double v)
{
    if (isfinite(v))
        printf("\"%s\": %.9g", key, v);
    else
        printf("\"%s\": null", key);
}

static void json_string(const char *key, const char *s)
{
    printf("\"%s\": \"", key);
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        if (*c == '"' || *c == '\\')
            printf("\\%c", *c);
        else if (*c < 0x20)
            printf("\\u%04x", *c);
        else
            putchar(*c);
    }
    putchar('"');
}

/* The metrics as JSON members (no braces). */
static void json_metrics(const gk_metrics *m)
{
    double psnr = (m->psnr > 999.0) ? 999.0 : m->psnr; /* +inf and > 999 both cap */
    json_number("rel_rmse", m->rel_rmse);
    fputs(", ", stdout);
    json_number("rel_mse", m->rel_mse);
    fputs(", ", stdout);
    json_number("rmse", m->rmse);
    fputs(", ", stdout);
    json_number("psnr", psnr);
    fputs(", ", stdout);
    json_number("ssim", m->ssim);
    fputs(", ", stdout);
    json_number("mean_ratio", m->mean_ratio);
    fputs(", ", stdout);
    json_number("max_error", m->max_error);
    printf(", \"max_error_at\": [%d, %d], ", m->max_error_at[0], m->max_error_at[1]);
    json_number("exposure", m->exposure);
    fputs(", ", stdout);
    json_number("ref_mean", m->ref_mean);
    fputs(", ", stdout);
    json_number("test_mean", m->test_mean);
    printf(", \"pixels\": %ld, \"nonfinite\": %ld", m->pixels, m->nonfinite);
}

typedef struct mask_report {
    const char *path;
    long pixels;
    gk_metrics inside, outside;
    int has_outside;  /* 0 when the mask selects every pixel */
} mask_report;

static void print_json(const char *ref_path, const char *test_path, const gk_image *ref, const gk_metrics *m,
                       const mask_report *mr)
{
    putchar('{');
    json_string("reference", ref_path);
    fputs(", ", stdout);
    json_string("test", test_path);
    printf(", \"width\": %d, \"height\": %d, \"channels\": %d, ", ref->width, ref->height, ref->channels);
    json_metrics(m);
    if (mr) {
        fputs(", \"mask\": {", stdout);
        json_string("file", mr->path);
        printf(", \"pixels\": %ld, \"inside\": {", mr->pixels);
        json_metrics(&mr->inside);
        fputs("}, \"outside\": ", stdout);
        if (mr->has_outside) {
            putchar('{');
            json_metrics(&mr->outside);
            putchar('}');
        } else {
            fputs("null", stdout);
        }
        putchar('}');
    }
    puts("}");
}

static void text_metrics(const gk_metrics *m)
{
    printf("%-11s %.6g\n", "rel_rmse", m->rel_rmse);
    printf("%-11s %.6g\n", "rel_mse", m->rel_mse);
    printf("%-11s %.6g\n", "rmse", m->rmse);
    printf("%-11s %.4f dB\n", "psnr", m->psnr); /* prints "inf dB" for identical images */
    printf("%-11s %.6f\n", "ssim", m->ssim);
    printf("%-11s %.6f\n", "mean_ratio", m->mean_ratio);
    printf("%-11s %.6g at [%d, %d]\n", "max_error", m->max_error, m->max_error_at[0], m->max_error_at[1]);
    printf("%-11s %.6g (ref mean %.6g, test mean %.6g)\n", "exposure", m->exposure, m->ref_mean, m->test_mean);
    if (m->nonfinite)
        printf("%-11s %ld NaN/inf values in the test image\n", "nonfinite", m->nonfinite);
}

static long count_nonfinite(const gk_image *img)
{
    long n = 0, count = (long)img->width * img->height * img->channels;
    for (long i = 0; i < count; i++)
        n += !isfinite(img->pixels[i]);
    return n;
}

static void print_text(const char *ref_path, const char *test_path, const gk_image *ref, const gk_metrics *m,
                       const mask_report *mr)
{
    printf("%-11s %s (%dx%d, %d channels)\n", "reference", ref_path, ref->width, ref->height, ref->channels);
    printf("%-11s %s\n", "test", test_path);
    text_metrics(m);
    if (!mr)
        return;
    printf("\ninside the mask %s (%ld pixels):\n", mr->path, mr->pixels);
    text_metrics(&mr->inside);
    if (mr->has_outside) {
        printf("\noutside the mask (%ld pixels):\n", mr->outside.pixels);
        text_metrics(&mr->outside);
    } else {
        printf("\noutside the mask: no pixel\n");
    }
}

/* Reads the mask image and computes the metrics inside and outside it. */
static int mask_metrics(const char *path, const gk_image *ref, const gk_image *test, double exposure,
                        mask_report *mr, gk_err *e)
{
    gk_image img = {0};
    if (gk_image_read(path, &img, e) != 0)
        return -1;
    int rc = -1;
    unsigned char *in = NULL;
    if (img.width != ref->width || img.height != ref->height) {
        gk_fail(e, GK_EINPUT, "mask %s is %dx%d, the images are %dx%d", path, img.width, img.height, ref->width,
                ref->height);
        goto out;
    }
    in = gk_mask_from_image(&img);
    if (!in) {
        gk_fail(e, GK_ERUNTIME, "out of memory for the mask %s", path);
        goto out;
    }
    size_t n = (size_t)img.width * img.height;
    mr->path = path;
    mr->pixels = gk_mask_count(in, img.width, img.height);
    if (mr->pixels == 0) {
        gk_fail(e, GK_EINPUT, "mask %s selects no pixel (no colour channel >= 0.5)", path);
        goto out;
    }
    /* The same auto exposure as the whole image, so the tonemap is the one it gets. */
    if (!(exposure > 0.0))
        exposure = gk_metrics_auto_exposure(ref);
    if (gk_metrics_compute_masked(ref, test, exposure, in, &mr->inside, e) != 0)
        goto out;
    mr->has_outside = mr->pixels < (long)n;
    for (size_t p = 0; p < n; p++)
        in[p] = !in[p];
    if (mr->has_outside && gk_metrics_compute_masked(ref, test, exposure, in, &mr->outside, e) != 0)
        goto out;
    rc = 0;
out:
    free(in);
    gk_image_free(&img);
    return rc;
}

static int bad_usage(const char *fmt, const char *arg)
{
    fputs("gikiosk compare: ", stderr);
    fprintf(stderr, fmt, arg);
    fputc('\n', stderr);
    usage(stderr);
    return 2;
}

static int parse_exposure(const char *s, double *out)
{
    char *end;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || !(v > 0.0) || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

int gk_cmd_compare(int argc, char **argv)
{
    const char *paths[2] = {NULL, NULL};
    int n_paths = 0, json = 0;
    const char *mask_path = NULL;
    double exposure = 0.0; /* auto */
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--exposure") || !strncmp(a, "--exposure=", 11)) {
            const char *v = a[10] == '=' ? a + 11 : (i + 1 < argc ? argv[++i] : NULL);
            if (!v)
                return bad_usage("--exposure needs a value%s", "");
            if (parse_exposure(v, &exposure) != 0)
                return bad_usage("--exposure: '%s' is not a positive number", v);
        } else if (!strcmp(a, "--mask") || !strncmp(a, "--mask=", 7)) {
            const char *v = a[6] == '=' ? a + 7 : (i + 1 < argc ? argv[++i] : NULL);
            if (!v || !*v)
                return bad_usage("--mask needs a file%s", "");
            mask_path = v;
        } else if (a[0] == '-' && a[1] != '\0') {
            return bad_usage("unknown option '%s'", a);
        } else if (n_paths < 2) {
            paths[n_paths++] = a;
        } else {
            return bad_usage("unexpected argument '%s' (give exactly REFERENCE and TEST)", a);
        }
    }
    if (n_paths != 2)
        return bad_usage("needs REFERENCE and TEST images%s", "");

    gk_image ref = {0}, test = {0};
    gk_metrics m;
    mask_report mr = {0};
    gk_err e = {0};
    int rc = 0;
    long ref_bad = 0;
    if (gk_image_read(paths[0], &ref, &e) != 0 || gk_image_read(paths[1], &test, &e) != 0 ||
        gk_metrics_compute(&ref, &test, exposure, &m, &e) != 0 ||
        (mask_path && mask_metrics(mask_path, &ref, &test, exposure, &mr, &e) != 0)) {
        fprintf(stderr, "gikiosk compare: %s\n", e.msg);
        rc = e.code ? e.code : 1;
    } else if ((ref_bad = count_nonfinite(&ref)) > 0) {
        /* a reference with NaN/inf is a bad file, not a measurement */
        fprintf(stderr, "gikiosk compare: %s: %ld NaN/inf values in the reference\n", paths[0], ref_bad);
        rc = 2;
    } else {
        if (json)
            print_json(paths[0], paths[1], &ref, &m, mask_path ? &mr : NULL);
        else
            print_text(paths[0], paths[1], &ref, &m, mask_path ? &mr : NULL);
        /* A NaN pixel makes the metrics NaN (or hides in them): never a success. */
        if (m.nonfinite > 0 || !isfinite(m.rmse) || !isfinite(m.ssim)) {
            fprintf(stderr, "gikiosk compare: %s: %ld NaN/inf values in the test image; the metrics are not "
                            "meaningful\n", paths[1], m.nonfinite);
            rc = 1;
        }
    }
    gk_image_free(&ref);
    gk_image_free(&test);
    return rc;
}
