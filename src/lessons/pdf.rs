//! The slides as one PDF: one page per slide, each page one image, embedded losslessly (8-bit
//! RGB, Flate-compressed), the page 960 × 540 points (13.33 × 7.5 in, a 16:9 presentation
//! page) whatever the slides' pixel size.

use pdf_writer::{Content, Filter, Finish, Name, Pdf, Rect, Ref};

/// Page width in points (1/72 in); the height follows the slide's aspect.
pub const PAGE_WIDTH_PT: f32 = 960.0;

/// One slide ready for the PDF: its size and its RGB bytes, Flate (zlib) compressed.
pub struct PdfPage {
    size: [u32; 2],
    flate_rgb: Vec<u8>,
}

impl PdfPage {
    /// Compresses `slide`'s colour (alpha dropped: slides are opaque).
    pub fn new(slide: &image::RgbaImage) -> PdfPage {
        let rgb: Vec<u8> = slide.pixels().flat_map(|p| [p.0[0], p.0[1], p.0[2]]).collect();
        let mut encoder = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
        std::io::Write::write_all(&mut encoder, &rgb).expect("writing to memory cannot fail");
        let flate_rgb = encoder.finish().expect("writing to memory cannot fail");
        PdfPage { size: slide.dimensions().into(), flate_rgb }
    }
}

/// The PDF of `pages`, in order.
pub fn slides_pdf(pages: &[PdfPage]) -> Vec<u8> {
    let mut pdf = Pdf::new();
    let catalog = Ref::new(1);
    let tree = Ref::new(2);
    pdf.catalog(catalog).pages(tree);
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
        writer.resources().x_objects().pair(Name(b"Slide"), image_id);
        writer.finish();
        let mut image = pdf.image_xobject(image_id, &page.flate_rgb);
        image.filter(Filter::FlateDecode);
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
        pdf.stream(content_id, &content.finish());
    }
    pdf.pages(tree).count(kids.len() as i32).kids(kids);
    pdf.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pdf_has_one_page_per_slide_and_its_pixels_unchanged() {
        let slide = image::RgbaImage::from_fn(4, 3, |x, y| image::Rgba([x as u8 * 60, y as u8 * 80, 7, 255]));
        let page = PdfPage::new(&slide);
        let mut decoder = flate2::read::ZlibDecoder::new(&page.flate_rgb[..]);
        let mut rgb = vec![];
        std::io::Read::read_to_end(&mut decoder, &mut rgb).unwrap();
        let expected: Vec<u8> = slide.pixels().flat_map(|p| [p.0[0], p.0[1], p.0[2]]).collect();
        assert_eq!(rgb, expected, "lossless");
        let pdf = slides_pdf(&[page, PdfPage::new(&slide)]);
        assert!(pdf.starts_with(b"%PDF-"));
        let text = String::from_utf8_lossy(&pdf);
        assert_eq!(text.matches("/Type /Page\n").count() + text.matches("/Type /Page ").count(), 2, "{text}");
    }
}
