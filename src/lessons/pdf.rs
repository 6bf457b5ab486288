//! The slides as one PDF: one page per slide, each page one image, embedded losslessly (8-bit
//! RGB, each row Paeth-filtered as PNG does, then Flate-compressed: PDF's PNG predictors), the
//! page 960 × 540 points (13.33 × 7.5 in, a 16:9 presentation page) whatever the slides' pixel
//! size. Each page also carries its title and caption as invisible text over the picture (so
//! a reader finds and copies them) and an outline entry with its title.

use pdf_writer::types::{PageMode, Predictor, TextRenderingMode};
use pdf_writer::{Content, Filter, Finish, Name, Pdf, Rect, Ref, Str, TextStr};

/// Page width in points (1/72 in); the height follows the slide's aspect.
pub const PAGE_WIDTH_PT: f32 = 960.0;

/// PNG's filter type byte of a Paeth-filtered row.
const PAETH: u8 = 4;

/// One slide ready for the PDF: its size, its RGB rows, Paeth-filtered and Flate (zlib)
/// compressed, and its title and caption as text.
pub struct PdfPage {
    size: [u32; 2],
    flate_rows: Vec<u8>,
    title: String,
    caption: String,
}

impl PdfPage {
    /// Filters and compresses `slide`'s colour (alpha dropped: slides are opaque); `title` and
    /// `caption` are the page's text.
    pub fn new(slide: &image::RgbaImage, title: &str, caption: &str) -> PdfPage {
        let rgb: Vec<u8> = slide.pixels().flat_map(|p| [p.0[0], p.0[1], p.0[2]]).collect();
        let filtered = paeth_rows(&rgb, slide.width() as usize * 3);
        let mut encoder = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
        std::io::Write::write_all(&mut encoder, &filtered).expect("writing to memory cannot fail");
        let flate_rows = encoder.finish().expect("writing to memory cannot fail");
        PdfPage { size: slide.dimensions().into(), flate_rows, title: title.to_owned(), caption: caption.to_owned() }
    }
}

/// `text` in the standard fonts' WinAnsiEncoding: Latin-1 and the typographic marks it has
/// as they are, the few others the lessons use spelled in ASCII ("│" as "|", "→" as "->"),
/// anything else as "?".
fn win_ansi(text: &str) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(text.len());
    for c in text.chars() {
        match c {
            ' '..='~' | '\u{a0}'..='\u{ff}' => bytes.push(c as u8),
            '\n' | '\t' => bytes.push(b' '),
            '–' => bytes.push(0x96),
            '—' => bytes.push(0x97),
            '‘' => bytes.push(0x91),
            '’' => bytes.push(0x92),
            '“' => bytes.push(0x93),
            '”' => bytes.push(0x94),
            '•' => bytes.push(0x95),
            '…' => bytes.push(0x85),
            '│' => bytes.push(b'|'),
            '−' => bytes.push(b'-'),
            '→' => bytes.extend(b"->"),
            '≥' => bytes.extend(b">="),
            '≤' => bytes.extend(b"<="),
            _ => bytes.push(b'?'),
        }
    }
    bytes
}

/// Characters per line of the caption's text: 12-point Helvetica averages under 6 points a
/// character, so a line stays within the page's 960 points.
const CAPTION_LINE_CHARS: usize = 120;

/// The page's title and caption as invisible text (rendering mode 3) in Helvetica, the
/// title along the top of a page `height_pt` tall and the caption under it in lines of at most
/// [`CAPTION_LINE_CHARS`] characters (broken between words).
fn page_text(content: &mut Content, page: &PdfPage, height_pt: f32) {
    content.begin_text();
    content.set_text_rendering_mode(TextRenderingMode::Invisible);
    content.set_font(Name(b"F1"), 24.0);
    content.next_line(36.0, height_pt - 48.0);
    content.show(Str(&win_ansi(&page.title)));
    content.set_font(Name(b"F1"), 12.0);
    content.next_line(0.0, -10.0);
    let mut line = String::new();
    for word in page.caption.split_whitespace() {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > CAPTION_LINE_CHARS {
            content.next_line(0.0, -14.0).show(Str(&win_ansi(&line)));
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    content.next_line(0.0, -14.0).show(Str(&win_ansi(&line)));
    content.end_text();
}

/// PNG's Paeth predictor of a byte from its left, upper and upper-left neighbours.
fn paeth(left: u8, up: u8, up_left: u8) -> u8 {
    let p = i16::from(left) + i16::from(up) - i16::from(up_left);
    let (pa, pb, pc) = ((p - i16::from(left)).abs(), (p - i16::from(up)).abs(), (p - i16::from(up_left)).abs());
    if pa <= pb && pa <= pc {
        left
    } else if pb <= pc {
        up
    } else {
        up_left
    }
}

/// `rgb` rows of `stride` bytes as PNG's Paeth-filtered rows: each a filter byte, then each
/// byte less its prediction (neighbours 3 bytes, one pixel, apart; zero outside the image).
fn paeth_rows(rgb: &[u8], stride: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(rgb.len() + rgb.len() / stride.max(1));
    let zero = vec![0; stride];
    for (y, row) in rgb.chunks_exact(stride).enumerate() {
        let up_row = if y == 0 { &zero[..] } else { &rgb[(y - 1) * stride..y * stride] };
        out.push(PAETH);
        for i in 0..stride {
            let (left, up_left) = if i >= 3 { (row[i - 3], up_row[i - 3]) } else { (0, 0) };
            out.push(row[i].wrapping_sub(paeth(left, up_row[i], up_left)));
        }
    }
    out
}

/// The PDF of `pages`, in order.
pub fn slides_pdf(pages: &[PdfPage]) -> Vec<u8> {
    let mut pdf = Pdf::new();
    let catalog = Ref::new(1);
    let tree = Ref::new(2);
    // After the pages' three objects each: the font, the outline and its items.
    let font = Ref::new(3 + 3 * pages.len() as i32);
    let outline = Ref::new(font.get() + 1);
    let item = |i: usize| Ref::new(outline.get() + 1 + i as i32);
    pdf.catalog(catalog).pages(tree).outlines(outline).page_mode(PageMode::UseOutlines);
    pdf.type1_font(font).base_font(Name(b"Helvetica")).encoding_predefined(Name(b"WinAnsiEncoding"));
    let mut kids = vec![];
    for (i, page) in pages.iter().enumerate() {
        let base = 3 + 3 * i as i32;
        let (page_id, image_id, content_id) = (Ref::new(base), Ref::new(base + 1), Ref::new(base + 2));
        kids.push(page_id);
        let [w, h] = page.size;
        let height_pt = PAGE_WIDTH_PT * h as f32 / w.max(1) as f32;
        let mut writer = pdf.page(page_id);
        writer.media_box(Rect::new(0.0, 0.0, PAGE_WIDTH_PT, height_pt));
        writer.parent(tree);
        writer.contents(content_id);
        let mut resources = writer.resources();
        resources.x_objects().pair(Name(b"Slide"), image_id);
        resources.fonts().pair(Name(b"F1"), font);
        resources.finish();
        writer.finish();
        let mut image = pdf.image_xobject(image_id, &page.flate_rows);
        image.filter(Filter::FlateDecode);
        image.decode_parms().predictor(Predictor::PngOptimum).colors(3).bits_per_component(8).columns(w as i32);
        image.width(w as i32);
        image.height(h as i32);
        image.color_space().device_rgb();
        image.bits_per_component(8);
        image.finish();
        let mut content = Content::new();
        content.save_state();
        content.transform([PAGE_WIDTH_PT, 0.0, 0.0, height_pt, 0.0, 0.0]);
        content.x_object(Name(b"Slide"));
        content.restore_state();
        page_text(&mut content, page, height_pt);
        pdf.stream(content_id, &content.finish());
        let mut entry = pdf.outline_item(item(i));
        entry.title(TextStr(&page.title)).parent(outline);
        if i > 0 {
            entry.prev(item(i - 1));
        }
        if i + 1 < pages.len() {
            entry.next(item(i + 1));
        }
        entry.dest().page(page_id).fit();
    }
    let mut contents = pdf.outline(outline);
    if !pages.is_empty() {
        contents.first(item(0)).last(item(pages.len() - 1));
    }
    contents.count(pages.len() as i32);
    contents.finish();
    pdf.pages(tree).count(kids.len() as i32).kids(kids);
    pdf.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pdf_has_one_page_per_slide_and_its_pixels_unchanged() {
        let slide = image::RgbaImage::from_fn(4, 3, |x, y| image::Rgba([x as u8 * 60, y as u8 * 80, 7, 255]));
        let page = PdfPage::new(&slide, "A → B", "caption");
        let mut decoder = flate2::read::ZlibDecoder::new(&page.flate_rows[..]);
        let mut filtered = vec![];
        std::io::Read::read_to_end(&mut decoder, &mut filtered).unwrap();
        // Undo the filter as a reader does: each byte plus the prediction from the decoded ones.
        let stride = 4 * 3;
        let mut rgb: Vec<u8> = vec![];
        for (y, row) in filtered.chunks_exact(stride + 1).enumerate() {
            assert_eq!(row[0], PAETH);
            for i in 0..stride {
                let at = |dy: usize, dx: usize| {
                    if y < dy || i < dx { 0 } else { rgb[(y - dy) * stride + i - dx] }
                };
                let predicted = paeth(if i >= 3 { at(0, 3) } else { 0 }, at(1, 0), at(1, 3));
                rgb.push(row[i + 1].wrapping_add(predicted));
            }
        }
        let expected: Vec<u8> = slide.pixels().flat_map(|p| [p.0[0], p.0[1], p.0[2]]).collect();
        assert_eq!(rgb, expected, "lossless");
        let pdf = slides_pdf(&[page, PdfPage::new(&slide, "second", "")]);
        assert!(pdf.starts_with(b"%PDF-"));
        let text = String::from_utf8_lossy(&pdf);
        assert_eq!(text.matches("/Type /Page\n").count() + text.matches("/Type /Page ").count(), 2, "{text}");
        assert!(text.contains("/Outlines") && text.contains("/Count 2"), "an outline of both pages");
        assert!(text.contains("(A -> B)") && text.contains("/BaseFont /Helvetica"), "the title as text");
    }
}
