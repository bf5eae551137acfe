/* What the lab's Allegro and GD peers cannot reach from Rust without
 * copying the libraries' struct layouts or macros: Allegro's start-up
 * call (its system id is a macro, and it takes C's errno and atexit),
 * and the rows of an Allegro bitmap (bmp->line[y]) and of a GD palette
 * image (im->pixels[y]), read back to judge what they drew. Every drawing
 * call is made from Rust, as declared in allegro.rs and gd.rs. */

#include <errno.h>
#include <stdlib.h>

#include <allegro.h>
#include <gd.h>

/* Allegro with no system driver: memory bitmaps only, no window. */
int lab_allegro_install(void)
{
   return install_allegro(SYSTEM_NONE, &errno, atexit);
}

unsigned char *lab_allegro_row(BITMAP *bmp, int y)
{
   return bmp->line[y];
}

unsigned char *lab_gd_row(gdImagePtr im, int y)
{
   return im->pixels[y];
}
